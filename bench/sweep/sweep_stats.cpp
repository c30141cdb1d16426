#include "bench/sweep/sweep_stats.h"

#include "bench/common/stats.h"
#include "render/image_compare.h"

namespace lgh::bench {

ErrorStats unshadowedError(const reference::ReferenceImage& ref, const ImageRGBA& image) {
  return errorOver(ref, ref.unshadowed, [&](std::uint32_t i) { return luminance(image.pixels[i]); });
}

ErrorStats shadowedError(const reference::ReferenceImage& ref, const ImageRGBA& irradiance,
                         const ImageRGBA* visibility) {
  if (!visibility)
    return errorOver(ref, ref.shadowed, [&](std::uint32_t i) { return luminance(irradiance.pixels[i]); });
  return errorOver(ref, ref.shadowed,
                   [&](std::uint32_t i) { return luminance(irradiance.pixels[i]) * double(visibility->pixels[i].r); });
}

ErrorStats exactRatioError(const reference::ReferenceImage& ref, const ImageRGBA& irradiance) {
  std::vector<double> ratio(irradiance.pixels.size(), 0.0);
  for (size_t k = 0; k < ref.pixels.size(); ++k) {
    const double unshadowed = luminance(ref.unshadowed[k]);
    ratio[ref.pixels[k]] = unshadowed > 0 ? luminance(ref.shadowed[k]) / unshadowed : 0.0;
  }
  return errorOver(ref, ref.shadowed, [&](std::uint32_t i) { return luminance(irradiance.pixels[i]) * ratio[i]; });
}

double median(const std::vector<double>& samples) { return samples.empty() ? kNaN : spreadOf(samples).median; }

double extrapolateLinear(const std::vector<std::pair<double, double>>& points, double at) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, k = 0;
  for (const auto& [x, y] : points) {
    sx += x, sy += y, sxx += x * x, sxy += x * y, k += 1;
  }
  if (k < 2) return kNaN;
  const double b = (k * sxy - sx * sy) / std::max(k * sxx - sx * sx, 1e-300), a = (sy - b * sx) / k;
  return a + b * at;
}

}  // namespace lgh::bench
