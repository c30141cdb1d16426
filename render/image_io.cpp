#include "render/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "shared/display_encode.h"

namespace lgh {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// Writes 3-channel pixels (rows top-down) beside the target, then renames: an interrupted write never
// clobbers an existing image. FLOAT data is linear HDR; UINT8 data is display-encoded sRGB.
void writePixels(const std::filesystem::path& path, int width, int height, OIIO::TypeDesc type, const void* pixels) {
  const std::filesystem::path temporary =
      path.parent_path() / (".tmp-" + path.filename().stem().string() + lowerExtension(path));
  auto out = OIIO::ImageOutput::create(temporary.string());
  if (!out) throw std::runtime_error(path.string() + ": cannot create an image writer (" + OIIO::geterror() + ")");
  OIIO::ImageSpec spec(width, height, 3, type);
  if (type == OIIO::TypeDesc::UINT8) spec.attribute("oiio:ColorSpace", "sRGB");
  const bool ok = out->open(temporary.string(), spec) && out->write_image(type, pixels) && out->close();
  if (!ok) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(path.string() + ": writing failed (" + out->geterror() + ")");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec)
    throw std::runtime_error(path.string() + ": could not move the finished image into place (" + ec.message() + ")");
}

}  // namespace

ToneMap parseToneMap(const std::string& name) {
  if (name == "clamp") return ToneMap::Clamp;
  if (name == "reinhard") return ToneMap::Reinhard;
  if (name == "aces") return ToneMap::Aces;
  throw std::invalid_argument("unknown tone map '" + name + "' (choose clamp, reinhard or aces)");
}

ImageRGBA fromGLRows(int width, int height, std::vector<glm::vec4> bottomUp) {
  ImageRGBA image{width, height, std::move(bottomUp)};
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(image.pixels.begin() + ptrdiff_t(y) * width, image.pixels.begin() + ptrdiff_t(y + 1) * width,
                     image.pixels.begin() + ptrdiff_t(height - 1 - y) * width);
  return image;
}

bool isHdrFormat(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

static_assert(std::uint32_t(ToneMap::Clamp) == gpu::kToneMapClamp &&
                  std::uint32_t(ToneMap::Reinhard) == gpu::kToneMapReinhard &&
                  std::uint32_t(ToneMap::Aces) == gpu::kToneMapAces,
              "ToneMap must list the curves in the order of shared/display_encode.h");

glm::vec3 displayEncode(const glm::vec3& linear, float exposureEV, ToneMap toneMap) {
  return gpu::encodeForDisplay(linear, exposureEV, std::uint32_t(toneMap));
}

void checkImagePath(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (!isHdrFormat(path) && ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".tif" && ext != ".tiff" &&
      ext != ".bmp")
    throw std::runtime_error(path.string() + ": unsupported image format '" + ext +
                             "' (use .exr, .hdr or .pfm for linear HDR; .png, .jpg, .tif or .bmp for display)");
  const std::filesystem::path folder = path.parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
    throw std::runtime_error(path.string() + ": the folder " + folder.string() + " does not exist");
}

void writeImage(const std::filesystem::path& path, const ImageRGBA& image, float exposureEV, ToneMap toneMap) {
  checkImagePath(path);
  const size_t count = size_t(image.width) * size_t(image.height);
  const int channels = 3;
  if (isHdrFormat(path)) {
    std::vector<float> linear(count * channels);
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < channels; ++c) linear[i * channels + size_t(c)] = image.pixels[i][c];
    writePixels(path, image.width, image.height, OIIO::TypeDesc::FLOAT, linear.data());
  } else {
    std::vector<std::uint8_t> display(count * channels);
    for (size_t i = 0; i < count; ++i) {
      const glm::vec3 e = displayEncode(glm::vec3(image.pixels[i]), exposureEV, toneMap);
      for (int c = 0; c < channels; ++c) display[i * channels + size_t(c)] = (unsigned char)std::lround(e[c] * 255.0f);
    }
    writePixels(path, image.width, image.height, OIIO::TypeDesc::UINT8, display.data());
  }
}

void writeDisplayImage(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  checkImagePath(path);
  if (isHdrFormat(path))
    throw std::runtime_error(path.string() + ": display-encoded pixels need a display format (.png, .jpg, .tif, .bmp)");
  if (rgb.size() != size_t(width) * size_t(height) * 3)
    throw std::invalid_argument(path.string() + ": pixel count does not match " + std::to_string(width) + " x " +
                                std::to_string(height));
  writePixels(path, width, height, OIIO::TypeDesc::UINT8, rgb.data());
}

}  // namespace lgh
