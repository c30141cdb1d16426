#pragma once
// The sweep's statistics: the error of an image against the exact reference, medians over repeats,
// and the linear fit that extrapolates a baseline's time to all lights.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "bench/reference/reference.h"
#include "render/image_io.h"

namespace lgh::bench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct ErrorStats {
  double rmse = kNaN, psnr = kNaN, mae = kNaN;
};

// Relative RMSE, PSNR and relative mean absolute error of the luminance of estimate(pixel) against the
// reference `values` over the reference's pixels:
//   rmse = sqrt(sum (a - r)^2 / sum r^2),  psnr = 10 log10(max r^2 / mean (a - r)^2)  (dB; 300 if exact),
//   mae = sum |a - r| / sum |r|  (a second measure that a few outlying pixels do not dominate).
// A non-finite estimate makes all NaN.
template <typename Estimate>
ErrorStats errorOver(const reference::ReferenceImage& ref, const std::vector<glm::dvec3>& values, Estimate&& estimate) {
  double squared = 0, norm = 0, peak = 0, absolute = 0, total = 0;
  for (size_t k = 0; k < ref.pixels.size(); ++k) {
    const double r = luminance(values[k]), a = estimate(ref.pixels[k]);
    if (!std::isfinite(a)) return {};
    squared += (a - r) * (a - r);
    norm += r * r;
    peak = std::max(peak, r);
    absolute += std::abs(a - r);
    total += std::abs(r);
  }
  ErrorStats e;
  e.rmse = std::sqrt(squared / std::max(norm, 1e-300));
  e.mae = absolute / std::max(total, 1e-300);
  const double mse = squared / double(std::max<size_t>(ref.pixels.size(), 1));
  e.psnr = mse > 0 ? std::min(300.0, 10.0 * std::log10(peak * peak / mse)) : 300.0;
  return e;
}
// Against the unshadowed reference: the luminance of `image`.
ErrorStats unshadowedError(const reference::ReferenceImage& ref, const ImageRGBA& image);
// Against the shadowed reference: the luminance of irradiance x visibility (Aov::Visibility's r), or
// of `irradiance` alone where the image is already shadowed (visibility null).
ErrorStats shadowedError(const reference::ReferenceImage& ref, const ImageRGBA& irradiance,
                         const ImageRGBA* visibility);
// Against the shadowed reference: the luminance of irradiance x the reference's own visibility ratio
// (shadowed / unshadowed luminance). The floor of any ratio estimate composited on this irradiance:
// what a shadow estimate would reach with infinitely many exact samples.
ErrorStats exactRatioError(const reference::ReferenceImage& ref, const ImageRGBA& irradiance);

// The median of the samples; NaN when there are none.
double median(const std::vector<double>& samples);

// The least-squares line y = a + b x through the points, at x = at; NaN with fewer than two points.
double extrapolateLinear(const std::vector<std::pair<double, double>>& points, double at);

}  // namespace lgh::bench
