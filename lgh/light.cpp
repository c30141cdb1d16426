#include "lgh/light.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>
#include <stdexcept>

namespace lgh {

namespace {

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The problem with one light, or "" if there is none.
std::string problemWith(const Light& light) {
  if (!isFinite(light.position)) return "non-finite position";
  if (!isFinite(light.intensity)) return "non-finite intensity";
  if (!isFinite(light.normal)) return "non-finite normal";
  if (light.intensity.x < 0.0f || light.intensity.y < 0.0f || light.intensity.z < 0.0f) return "negative intensity";
  if (light.normal != glm::vec3(0.0f)) {
    const double length = glm::length(glm::dvec3(light.normal));
    if (std::abs(length - 1.0) > 1e-3) return "normal is neither zero nor unit length";
  }
  return {};
}

}  // namespace

glm::dvec3 unitNormal(const Light& light) {
  const glm::dvec3 normal(light.normal);
  const double length = glm::length(normal);
  return length > 0.0 ? normal / length : glm::dvec3(0.0);
}

std::string validateLights(const std::vector<Light>& lights) {
  for (size_t i = 0; i < lights.size(); ++i) {
    const std::string problem = problemWith(lights[i]);
    if (!problem.empty()) {
      std::ostringstream message;
      message << "light " << i << ": " << problem;
      return message.str();
    }
  }
  return {};
}

void requireValidLights(const std::vector<Light>& lights) {
  const std::string problem = validateLights(lights);
  if (!problem.empty()) throw std::invalid_argument("lgh: invalid input, " + problem);
}

}  // namespace lgh
