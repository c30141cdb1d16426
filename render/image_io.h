#pragma once
// Writing rendered images. HDR formats (.exr, .hdr, .pfm) get linear floats as rendered; display
// formats (.png, .jpg, .tif, .bmp) get exposure, a tone curve and the sRGB transfer function.

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lgh {

enum class ToneMap { Clamp, Reinhard, Aces };
ToneMap parseToneMap(const std::string& name);  // "clamp", "reinhard", "aces"

struct ImageRGBA {
  int width = 0, height = 0;
  std::vector<glm::vec4> pixels;  // rows top-down (already flipped from GL's bottom-up)
  const glm::vec4& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

// GL readbacks are bottom-up; images are top-down.
ImageRGBA fromGLRows(int width, int height, std::vector<glm::vec4> bottomUp);

bool isHdrFormat(const std::filesystem::path& path);
// Throws std::runtime_error("<path>: <problem>") if `path` has an unsupported extension or its folder
// does not exist; called before rendering so a typo costs milliseconds, not a render.
void checkImagePath(const std::filesystem::path& path);
// Throws std::runtime_error("<path>: <problem>") on an unknown extension or a write failure. The file
// is written next to its destination and renamed into place, so a failed write never leaves a
// half-written image where a good one was.
void writeImage(const std::filesystem::path& path, const ImageRGBA& image, float exposureEV = 0.0f,
                ToneMap toneMap = ToneMap::Aces);

// Writes pixels that are already display-encoded (8-bit sRGB RGB, rows top-down), such as a viewer
// screenshot of what its window shows; display formats only. Same errors and atomic rename as writeImage.
void writeDisplayImage(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb);

// Display mapping of one linear value (exposure, tone curve, sRGB encoding) in [0, 1].
glm::vec3 displayEncode(const glm::vec3& linear, float exposureEV, ToneMap toneMap);

}  // namespace lgh
