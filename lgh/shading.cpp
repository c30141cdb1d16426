#include "lgh/shading.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace lgh {

double emissionLobe(const glm::dvec3& meanNormal, double omniFraction, const glm::dvec3& u) {
  const double directional = std::max(0.0, glm::dot(meanNormal, u));
  const double uniform = (1.0 - glm::length(meanNormal) - omniFraction) / 4.0 + omniFraction;
  return std::max(0.0, directional + uniform);
}

glm::dvec3 lightContribution(const glm::dvec3& lightPos, const glm::dvec3& intensity, const glm::dvec3& meanNormal,
                             double omniFraction, const glm::dvec3& x, const glm::dvec3* nx, double clampDistance) {
  const glm::dvec3 toLight = lightPos - x;
  const double d = glm::length(toLight);
  const glm::dvec3 omega = d > 0.0 ? toLight / d : (nx ? *nx : glm::dvec3(0.0, 0.0, 1.0));
  const double cosine = nx ? std::max(0.0, glm::dot(*nx, omega)) : 1.0;
  if (cosine == 0.0) return glm::dvec3(0.0);
  const double lobe = emissionLobe(meanNormal, omniFraction, -omega);
  const double distanceSq = std::max({d * d, clampDistance * clampDistance, kMinDistanceSq});
  return intensity * (cosine * lobe / distanceSq);
}

}  // namespace lgh
