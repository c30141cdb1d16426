#include "lgh/evaluate.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "lgh/blending.h"
#include "lgh/shading.h"

namespace lgh {

namespace {

// An input light in the evaluator's terms: a cluster of one.
glm::dvec3 contributionOf(const Light& light, const glm::dvec3& x, const glm::dvec3* nx, double clampDistance) {
  return lightContribution(glm::dvec3(light.position), glm::dvec3(light.intensity), unitNormal(light),
                           omniFraction(light), x, nx, clampDistance);
}

glm::dvec3 contributionOf(const GridLight& light, const glm::dvec3& x, const glm::dvec3* nx, double clampDistance) {
  return lightContribution(light.position, light.intensity, light.meanNormal, light.omniFraction, x, nx, clampDistance);
}

// Adds the blended contributions of one level's lights. The distance decides the weight first, so
// lights outside the level's band cost a subtraction and a square root, not a shading evaluation.
template <typename LevelLight>
void accumulateLevel(const std::vector<LevelLight>& lights, LevelRole role, double radius, const glm::dvec3& x,
                     const glm::dvec3* nx, double clampDistance, glm::dvec3& sum, EvalStats* stats) {
  for (const LevelLight& light : lights) {
    const double d = glm::distance(glm::dvec3(light.position), x);
    const double weight = blendWeight(role, d, radius);
    if (weight == 0.0) continue;
    sum += weight * contributionOf(light, x, nx, clampDistance);
    if (stats) ++stats->lightsVisited;
  }
}

}  // namespace

glm::dvec3 evaluateExact(const std::vector<Light>& lights, const glm::dvec3& x, const glm::dvec3* nx,
                         const EvalOptions& options, EvalStats* stats) {
  glm::dvec3 sum(0.0);
  accumulateLevel(lights, LevelRole::Only, 0.0, x, nx, options.clampDistance, sum, stats);
  return sum;
}

glm::dvec3 evaluateHierarchy(const Hierarchy& hierarchy, const std::vector<Light>& lights, const glm::dvec3& x,
                             const glm::dvec3* nx, const EvalOptions& options, EvalStats* stats) {
  const GridGeometry& grid = hierarchy.grid;
  // levels.size() == L + 1 for a built hierarchy; a default-constructed one degrades to brute force.
  const int topLevel = std::max(0, std::min(grid.levels, int(hierarchy.levels.size()) - 1));
  const int firstLevel = std::clamp(options.firstLevel, 0, topLevel);
  glm::dvec3 sum(0.0);
  for (int level = firstLevel; level <= topLevel; ++level) {
    const LevelRole role = levelRole(level, firstLevel, topLevel);
    const double radius = grid.radius(level, options.alpha);
    if (level == 0)
      accumulateLevel(lights, role, radius, x, nx, options.clampDistance, sum, stats);
    else
      accumulateLevel(hierarchy.levels[level], role, radius, x, nx, options.clampDistance, sum, stats);
  }
  return sum;
}

}  // namespace lgh
