#pragma once

#include <cstddef>
#include <vector>

namespace lgh::bench {

// A frame's shadowed estimate I V against the reference R = R_u V_ref (R_u: the unshadowed sum, V_ref =
// R / R_u its visibility), per pixel. The error I V - R splits exactly into the irradiance's part
// (I - R_u) V_ref and the visibility's part I (V - V_ref), so that lgh-bench motion can say which of the
// two flickers: a history of the visibility ratio can take out only the second.
struct ErrorParts {
  std::vector<double> irradiance, visibility;
};

inline ErrorParts errorParts(const std::vector<double>& irradiance, const std::vector<double>& visibility,
                             const std::vector<double>& unshadowedReference,
                             const std::vector<double>& shadowedReference) {
  ErrorParts parts;
  for (std::size_t k = 0; k < shadowedReference.size(); ++k) {
    const double referenceVisibility = unshadowedReference[k] > 0 ? shadowedReference[k] / unshadowedReference[k] : 0.0;
    parts.irradiance.push_back((irradiance[k] - unshadowedReference[k]) * referenceVisibility);
    parts.visibility.push_back(irradiance[k] * (visibility[k] - referenceVisibility));
  }
  return parts;
}

}  // namespace lgh::bench
