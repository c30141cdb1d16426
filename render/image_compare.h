#pragma once
// Image error metrics on luminance (Rec. 709 weights), shared by tests, benchmarks and sweeps so that
// every reported error means the same thing.

#include <algorithm>
#include <cmath>

#include "lgh/light.h"
#include "render/image_io.h"

namespace lgh {

inline double luminance(const glm::vec4& c) { return luminance(glm::dvec3(c)); }

// sqrt(sum (a - b)^2 / sum b^2) over the pixels' luminance; b is the reference.
inline double relativeRmse(const ImageRGBA& a, const ImageRGBA& reference) {
  double error = 0, norm = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double r = luminance(reference.pixels[i]), d = luminance(a.pixels[i]) - r;
    error += d * d;
    norm += r * r;
  }
  return std::sqrt(error / std::max(norm, 1e-300));
}

inline double meanLuminance(const ImageRGBA& image) {
  double sum = 0;
  for (const glm::vec4& p : image.pixels) sum += luminance(p);
  return sum / double(std::max<size_t>(image.pixels.size(), 1));
}

}  // namespace lgh
