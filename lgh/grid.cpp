#include "lgh/grid.h"

#include <glm/common.hpp>
#include <stdexcept>
#include <string>
#include <unordered_set>

namespace lgh {

namespace {

bool isLit(const Light& light) { return luminance(glm::dvec3(light.intensity)) > 0.0; }

// Axis-aligned bounds of the lights that matter. Dark lights neither emit nor get splatted, so
// letting a far-away dark light stretch the grid would only waste resolution.
struct Bounds {
  glm::dvec3 lower{0.0}, upper{0.0};
  bool empty = true;

  void grow(const glm::dvec3& p) {
    lower = empty ? p : glm::min(lower, p);
    upper = empty ? p : glm::max(upper, p);
    empty = false;
  }
};

Bounds lightBounds(const std::vector<Light>& lights) {
  Bounds litBounds, allBounds;
  for (const Light& light : lights) {
    allBounds.grow(glm::dvec3(light.position));
    if (isLit(light)) litBounds.grow(glm::dvec3(light.position));
  }
  return litBounds.empty ? allBounds : litBounds;
}

// makeGrid without the O(N) validation, for callers that validated already.
GridGeometry gridAround(const Bounds& bounds, int levels, double eMin) {
  const glm::dvec3 extent = bounds.upper - bounds.lower;
  const double longestEdge = std::max({extent.x, extent.y, extent.z});
  const double edge = std::max(longestEdge, eMin);
  GridGeometry grid;
  grid.levels = levels;
  // The 1% margin keeps the extreme lights off the top cell's faces, so clamping cell indices
  // (forEachCorner) only ever absorbs rounding.
  grid.topCellSize = 1.01 * (edge > 0.0 ? edge : 1.0);
  const glm::dvec3 centre = bounds.empty ? glm::dvec3(0.0) : 0.5 * (bounds.lower + bounds.upper);
  grid.origin = bounds.empty ? glm::dvec3(0.0) : centre - 0.5 * grid.topCellSize;
  return grid;
}

void checkLevels(int levels) {
  if (levels < 0 || levels > kMaxLevels)
    throw std::invalid_argument("lgh: levels must be in [0, " + std::to_string(kMaxLevels) + "], got " +
                                std::to_string(levels));
}

void checkEMin(double eMin) {
  if (!std::isfinite(eMin)) throw std::invalid_argument("lgh: eMin must be finite");
}

}  // namespace

GridGeometry makeGrid(const std::vector<Light>& lights, int levels, double eMin) {
  checkLevels(levels);
  checkEMin(eMin);
  requireValidLights(lights);
  return gridAround(lightBounds(lights), levels, eMin);
}

GridGeometry makeGridAround(const glm::dvec3& lower, const glm::dvec3& upper, int levels, double eMin) {
  checkLevels(levels);
  checkEMin(eMin);
  Bounds bounds;
  bounds.grow(lower);
  bounds.grow(upper);
  return gridAround(bounds, levels, eMin);
}

size_t countFinestVertices(const std::vector<Light>& lights, const GridGeometry& grid, size_t stopAt) {
  if (grid.levels < 1) return 0;
  std::unordered_set<uint64_t> touched;
  for (const Light& light : lights) {
    if (!isLit(light)) continue;
    forEachCorner(grid, 1, glm::dvec3(light.position),
                  [&](const glm::ivec3& vertex, double, const glm::dvec3&) { touched.insert(packVertex(vertex)); });
    if (touched.size() >= stopAt) return stopAt;
  }
  return touched.size();
}

int chooseLevelCount(const std::vector<Light>& lights, double eMin, int maxLevels) {
  checkEMin(eMin);
  requireValidLights(lights);
  maxLevels = std::clamp(maxLevels, 1, kMaxLevels);
  size_t litCount = 0;
  for (const Light& light : lights) litCount += isLit(light) ? 1 : 0;
  // |S1| < N/2  <=>  |S1| < ceil(N/2): counting can stop once it reaches ceil(N/2).
  const size_t tooMany = (litCount + 1) / 2;
  if (tooMany == 0) return 1;

  // |S1| grows with L (finer cells split the same lights over more vertices), so the answer is the
  // last L of the qualifying run that starts at L = 1.
  const Bounds bounds = lightBounds(lights);
  int chosen = 1;
  for (int levels = 1; levels <= maxLevels; ++levels) {
    const GridGeometry grid = gridAround(bounds, levels, eMin);
    if (countFinestVertices(lights, grid, tooMany) >= tooMany) break;
    chosen = levels;
  }
  return chosen;
}

}  // namespace lgh
