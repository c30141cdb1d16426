#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <unordered_map>

#include "lgh/hierarchy.h"

namespace lgh {

namespace {

// What one source (an input light, or a grid light of the level below) brings to a vertex.
// An input light is a cluster of one: no spread, its own normal, omni or not.
struct Emitter {
  glm::dvec3 position;
  glm::dvec3 intensity;
  glm::dvec3 variance;
  glm::dvec3 normal;
  double omniFraction;
};

Emitter asEmitter(const Light& light) {
  return {glm::dvec3(light.position), glm::dvec3(light.intensity), glm::dvec3(0.0), unitNormal(light),
          omniFraction(light)};
}

Emitter asEmitter(const GridLight& light) {
  return {light.position, light.intensity, light.variance, light.meanNormal, light.omniFraction};
}

// The sums a vertex collects (see hierarchy.h), offsets taken from the vertex itself.
struct VertexSums {
  double W = 0.0;
  glm::dvec3 D{0.0}, Q{0.0}, I{0.0}, N{0.0};
  double O = 0.0;

  void add(const Emitter& emitter, double importance, double w, const glm::dvec3& offset) {
    const double wa = w * importance;
    W += wa;
    D += wa * offset;
    Q += wa * (emitter.variance + offset * offset);
    I += w * emitter.intensity;
    N += wa * emitter.normal;
    O += wa * emitter.omniFraction;
  }

  GridLight finalise(const glm::ivec3& vertex, const glm::dvec3& vertexPosition) const {
    const glm::dvec3 mean = D / W;
    GridLight light;
    light.position = vertexPosition + mean;
    light.intensity = I;
    light.variance = glm::max(Q / W - mean * mean, glm::dvec3(0.0));
    // |N| <= W - O and O <= W hold exactly; the clamps only absorb rounding.
    light.meanNormal = N / W;
    const double normalLength = glm::length(light.meanNormal);
    if (normalLength > 1.0) light.meanNormal /= normalLength;
    light.omniFraction = std::clamp(O / W, 0.0, 1.0);
    light.vertex = vertex;
    return light;
  }
};

// Splats every emitter of non-zero luminance into the vertices of its cell at `level` and turns each
// vertex that received light into a grid light. Scatter and gather differ only in what they pass.
template <typename Sources>
std::vector<GridLight> splatIntoLevel(const Sources& sources, const GridGeometry& grid, int level) {
  std::unordered_map<uint64_t, VertexSums> sums;
  // At most 8 vertices per source and never more than the level has: reserving that bound avoids
  // rehashing without ever allocating for the empty part of the grid.
  const double vertexCount = std::pow(double(grid.cellsPerAxis(level)) + 1.0, 3.0);
  sums.reserve(size_t(std::min(8.0 * double(sources.size()), vertexCount)));
  for (const auto& source : sources) {
    const Emitter emitter = asEmitter(source);
    const double importance = luminance(emitter.intensity);
    if (!(importance > 0.0)) continue;
    forEachCorner(grid, level, emitter.position,
                  [&](const glm::ivec3& vertex, double w, const glm::dvec3& vertexPosition) {
                    sums[packVertex(vertex)].add(emitter, importance, w, emitter.position - vertexPosition);
                  });
  }

  // Deterministic order (by vertex key) so two builds can be compared light by light.
  std::vector<std::pair<uint64_t, const VertexSums*>> occupied;
  occupied.reserve(sums.size());
  for (const auto& [key, vertexSums] : sums)
    if (vertexSums.W > 0.0) occupied.emplace_back(key, &vertexSums);
  std::sort(occupied.begin(), occupied.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

  std::vector<GridLight> lights;
  lights.reserve(occupied.size());
  for (const auto& [key, vertexSums] : occupied) {
    const glm::ivec3 vertex = unpackVertex(key);
    lights.push_back(vertexSums->finalise(vertex, grid.vertexPosition(level, vertex)));
  }
  return lights;
}

Hierarchy emptyHierarchy(const std::vector<Light>& lights, const GridGeometry& grid) {
  requireValidLights(lights);
  const bool finite = std::isfinite(grid.topCellSize) && std::isfinite(grid.origin.x) && std::isfinite(grid.origin.y) &&
                      std::isfinite(grid.origin.z);
  if (grid.levels < 0 || grid.levels > kMaxLevels || !(grid.topCellSize > 0.0) || !finite)
    throw std::invalid_argument("lgh: invalid grid geometry");
  Hierarchy hierarchy;
  hierarchy.grid = grid;
  hierarchy.levels.resize(size_t(grid.levels) + 1);
  return hierarchy;
}

}  // namespace

size_t Hierarchy::lightCount() const {
  size_t count = 0;
  for (const auto& level : levels) count += level.size();
  return count;
}

Hierarchy buildScatter(const std::vector<Light>& lights, const GridGeometry& grid) {
  Hierarchy hierarchy = emptyHierarchy(lights, grid);
  for (int level = 1; level <= grid.levels; ++level) hierarchy.levels[level] = splatIntoLevel(lights, grid, level);
  return hierarchy;
}

Hierarchy buildGather(const std::vector<Light>& lights, const GridGeometry& grid) {
  Hierarchy hierarchy = emptyHierarchy(lights, grid);
  if (grid.levels >= 1) hierarchy.levels[1] = splatIntoLevel(lights, grid, 1);
  // The paper's gather lets parent vertex V collect the children whose centres lie in the 8 cells
  // around V. Those are exactly the children whose own cell has V as a corner, so splatting each
  // child into its cell computes the same sums, without atomics, from the child's side. (A GPU
  // gather finds them by scanning child vertices near V: a child's centre is within one child cell
  // of its vertex, which bounds that scan.)
  for (int level = 2; level <= grid.levels; ++level)
    hierarchy.levels[level] = splatIntoLevel(hierarchy.levels[level - 1], grid, level);
  return hierarchy;
}

}  // namespace lgh
