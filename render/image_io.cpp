#include "render/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace lgh {
namespace {

float srgbEncode(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
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

glm::vec3 displayEncode(const glm::vec3& linear, float exposureEV, ToneMap toneMap) {
  glm::vec3 c = glm::max(linear, glm::vec3(0.0f)) * std::exp2(exposureEV);
  switch (toneMap) {
    case ToneMap::Clamp:
      break;
    case ToneMap::Reinhard:
      c = c / (glm::vec3(1.0f) + c);
      break;
    case ToneMap::Aces:  // Narkowicz's fit of the ACES filmic curve
      c = (c * (2.51f * c + 0.03f)) / (c * (2.43f * c + 0.59f) + 0.14f);
      break;
  }
  return {srgbEncode(c.r), srgbEncode(c.g), srgbEncode(c.b)};
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
  const std::string ext = lowerExtension(path);
  const bool hdr = isHdrFormat(path);
  const size_t count = size_t(image.width) * size_t(image.height);
  const int channels = 3;
  std::vector<float> linear;
  std::vector<unsigned char> display;
  if (hdr) {
    linear.resize(count * channels);
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < channels; ++c) linear[i * channels + size_t(c)] = image.pixels[i][c];
  } else {
    display.resize(count * channels);
    for (size_t i = 0; i < count; ++i) {
      const glm::vec3 e = displayEncode(glm::vec3(image.pixels[i]), exposureEV, toneMap);
      for (int c = 0; c < channels; ++c) display[i * channels + size_t(c)] = (unsigned char)std::lround(e[c] * 255.0f);
    }
  }

  // Write beside the target, then rename: an interrupted write never clobbers an existing image.
  const std::filesystem::path temporary = path.parent_path() / (".tmp-" + path.filename().stem().string() + ext);
  auto out = OIIO::ImageOutput::create(temporary.string());
  if (!out) throw std::runtime_error(path.string() + ": cannot create an image writer (" + OIIO::geterror() + ")");
  OIIO::ImageSpec spec(image.width, image.height, channels, hdr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!hdr) spec.attribute("oiio:ColorSpace", "sRGB");
  const bool ok = out->open(temporary.string(), spec) &&
                  out->write_image(hdr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8,
                                   hdr ? static_cast<const void*>(linear.data()) : display.data()) &&
                  out->close();
  if (!ok) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(path.string() + ": writing failed (" + out->geterror() + ")");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) throw std::runtime_error(path.string() + ": could not move the finished image into place (" + ec.message() + ")");
}

}  // namespace lgh
