#pragma once
// Images as float32 arrays (height, width, 3) in NumPy's .npy format, for bench/sweep/plot_sweep.py.

#include <cstddef>
#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

namespace lgh::bench {

// rgb: height x width x 3 floats, rows top-down. Throws std::runtime_error when the file cannot be written.
void writeNpy(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgb);

// pixel(i) for i in [0, width x height), rows top-down.
template <typename PixelFn>
void writeImageNpy(const std::filesystem::path& path, int width, int height, PixelFn&& pixel) {
  std::vector<float> rgb(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
    const glm::vec3 c = pixel(i);
    for (int k = 0; k < 3; ++k) rgb[3 * i + size_t(k)] = c[k];
  }
  writeNpy(path, width, height, rgb);
}

}  // namespace lgh::bench
