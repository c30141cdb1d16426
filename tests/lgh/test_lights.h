#pragma once

// Light sets and small checks shared by the lgh test suites: the random sets of the accuracy
// experiments and the extreme sets of docs/design.md §8.

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "lgh/hierarchy.h"
#include "lgh/light.h"

namespace lgh::test {

// The eMin every test passes: small against the unit-scale sets, large against rounding.
constexpr double kEMin = 1e-4;

inline glm::dvec3 randomUnitVector(std::mt19937_64& rng) {
  std::normal_distribution<double> gaussian;
  for (;;) {
    const glm::dvec3 v(gaussian(rng), gaussian(rng), gaussian(rng));
    const double length = glm::length(v);
    if (length > 1e-6) return v / length;
  }
}

// N lights uniform in the cube [corner, corner + size]^3 with grey intensity U[0.5, 2] (the setup of
// docs/design.md §7's yardstick); oriented lights get a random unit normal.
inline std::vector<Light> randomCube(size_t count, uint64_t seed, bool oriented, glm::dvec3 corner = glm::dvec3(0.0),
                                     double size = 1.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), grey(0.5, 2.0);
  std::vector<Light> lights(count);
  for (Light& light : lights) {
    light.position = glm::vec3(corner + size * glm::dvec3(unit(rng), unit(rng), unit(rng)));
    light.intensity = glm::vec3(float(grey(rng)));
    if (oriented) light.normal = glm::vec3(randomUnitVector(rng));
  }
  return lights;
}

// Coloured lights whose intensities span 1e-8..1e8 (log-uniform), half oriented, a few dark.
inline std::vector<Light> wideIntensities(size_t count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-8.0, 8.0);
  std::vector<Light> lights(count);
  for (size_t i = 0; i < count; ++i) {
    Light& light = lights[i];
    light.position = glm::vec3(unit(rng), unit(rng), unit(rng));
    const double scale = std::pow(10.0, exponent(rng));
    light.intensity = i % 17 == 0 ? glm::vec3(0.0f) : glm::vec3(glm::dvec3(unit(rng), unit(rng), unit(rng)) * scale);
    if (i % 2 == 0) light.normal = glm::vec3(randomUnitVector(rng));
  }
  return lights;
}

// docs/design.md §8, as named light sets (zero lights included).
inline std::vector<std::pair<std::string, std::vector<Light>>> extremeSets() {
  std::vector<std::pair<std::string, std::vector<Light>>> sets;
  sets.emplace_back("zero lights", std::vector<Light>{});
  sets.emplace_back("one light", std::vector<Light>{{glm::vec3(0.3f, -2.0f, 7.0f), glm::vec3(1.0f, 2.0f, 3.0f),
                                                     glm::vec3(0.0f, 1.0f, 0.0f)}});
  {
    std::vector<Light> coincident = randomCube(2000, 11, true);
    for (Light& light : coincident) light.position = glm::vec3(0.25f, 0.5f, -1.0f);
    sets.emplace_back("all lights at one point", coincident);
  }
  {
    std::vector<Light> plane = randomCube(2000, 12, false);
    for (Light& light : plane) light.position.z = 0.375f;
    sets.emplace_back("all lights on a plane", plane);
  }
  sets.emplace_back("intensities 1e-8..1e8", wideIntensities(2000, 13));
  sets.emplace_back("offset by 1e5", randomCube(2000, 14, true, glm::dvec3(1e5, -1e5, 1e5), 10.0));
  {
    std::vector<Light> dark = randomCube(100, 15, false);
    for (Light& light : dark) light.intensity = glm::vec3(0.0f);
    sets.emplace_back("all lights dark", dark);
  }
  return sets;
}

inline bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline glm::dvec3 totalIntensity(const std::vector<Light>& lights) {
  glm::dvec3 sum(0.0);
  for (const Light& light : lights) sum += glm::dvec3(light.intensity);
  return sum;
}

inline glm::dvec3 totalIntensity(const std::vector<GridLight>& lights) {
  glm::dvec3 sum(0.0);
  for (const GridLight& light : lights) sum += light.intensity;
  return sum;
}

// Random points in the cube [lower, upper] grown by `margin` on every side.
inline std::vector<glm::dvec3> randomPoints(size_t count, uint64_t seed, glm::dvec3 lower, glm::dvec3 upper,
                                            double margin = 0.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::dvec3> points(count);
  for (glm::dvec3& p : points)
    p = lower - margin + (upper - lower + 2.0 * margin) * glm::dvec3(unit(rng), unit(rng), unit(rng));
  return points;
}

}  // namespace lgh::test
