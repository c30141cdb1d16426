#pragma once

// The nested cubic grids of the hierarchy: where they sit, how big their cells are, and how a point
// is spread over the 8 vertices of the cell that holds it (trilinear splatting). Scatter, gather and
// the automatic level count all go through `forEachCorner`, so they agree on every weight.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "lgh/light.h"

namespace lgh {

// Vertex coordinates are packed 21 bits per axis into one 64-bit key. Level 1 of an L-level grid has
// 2^(L-1) + 1 vertices per axis, so L = 21 is the deepest hierarchy whose coordinates fit.
constexpr int kMaxLevels = 21;

// One cube of size H (the top level, a single cell) subdivided into levels 1..L.
// Level l has cell size h_l = H / 2^(L-l) and (2^(L-l)+1)^3 vertices, so h_{l+1} = 2 h_l: that
// doubling is what makes the blending functions of adjacent levels meet (blending.h).
// `levels == 0` is legal and means "no grid": the evaluator then sums S0 by brute force.
struct GridGeometry {
  glm::dvec3 origin{0.0};    // min corner of the single top-level cell
  double topCellSize = 1.0;  // H = 1.01 * max(E, eMin), cube centred on the light bounds
  int levels = 1;            // L

  // h_l = H * 2^(l - L). Level 0 (S0, the input lights) gets h_0 = h_1 / 2 by the same formula;
  // it only serves as the base of S0's blending radius R_0 = alpha h_0.
  double cellSize(int level) const { return std::ldexp(topCellSize, level - levels); }
  double radius(int level, double alpha) const { return alpha * cellSize(level); }
  int cellsPerAxis(int level) const { return 1 << (levels - level); }
  glm::dvec3 vertexPosition(int level, const glm::ivec3& vertex) const {
    return origin + glm::dvec3(vertex) * cellSize(level);
  }
};

// Builds the grid for `levels` (0..kMaxLevels) levels around the lights of non-zero luminance (around
// all lights if every one is dark; origin 0 and H = 1.01 eMin if there are none). eMin keeps one light
// or coincident lights from producing a zero-size cell; a non-positive eMin with such lights falls back
// to a length of 1. Throws std::invalid_argument for invalid lights (validateLights) or levels.
GridGeometry makeGrid(const std::vector<Light>& lights, int levels, double eMin);

// The same grid for lights whose lit positions span [lower, upper], for callers that computed the
// bounds themselves (the GPU build reduces them on the GPU and derives the grid here, so both builds
// share one definition of H and the origin).
GridGeometry makeGridAround(const glm::dvec3& lower, const glm::dvec3& upper, int levels, double eMin);

// The paper's automatic level count: the largest L in [1, maxLevels] whose level S1 (built from the
// lights) has fewer than N/2 grid lights, N = number of lights with non-zero luminance; 1 if none does.
// L grows until the first failure; each trial stops counting as soon as it reaches N/2, so the cost is
// O(N) per trial and memory follows the occupied vertices.
int chooseLevelCount(const std::vector<Light>& lights, double eMin, int maxLevels = kMaxLevels);

// Number of distinct level-1 vertices that receive a non-zero trilinear weight from a light of
// non-zero luminance, counted up to `stopAt` (the count returned never exceeds it).
size_t countFinestVertices(const std::vector<Light>& lights, const GridGeometry& grid, size_t stopAt = SIZE_MAX);

// 21 bits per axis, x lowest. Sorting by key orders vertices z-major, then y, then x.
inline uint64_t packVertex(const glm::ivec3& v) {
  return uint64_t(v.x) | (uint64_t(v.y) << 21) | (uint64_t(v.z) << 42);
}
inline glm::ivec3 unpackVertex(uint64_t key) {
  constexpr uint64_t mask = (uint64_t(1) << 21) - 1;
  return glm::ivec3(int(key & mask), int((key >> 21) & mask), int((key >> 42) & mask));
}

// Calls visit(vertex, weight, vertexPosition) for each corner of the level-`level` cell containing p
// whose trilinear weight w = prod_axis (1 - |p - v_pos| / h) is non-zero. The cell index is clamped
// to the grid, so a point on the far boundary (or a rounding hair outside) still lands in a cell;
// the local coordinate is clamped to [0, 1] with it, which keeps every weight in [0, 1] and their sum 1.
template <typename Visit>
void forEachCorner(const GridGeometry& grid, int level, const glm::dvec3& p, Visit&& visit) {
  const double h = grid.cellSize(level);
  const double lastCell = double(grid.cellsPerAxis(level) - 1);
  glm::ivec3 cell;
  glm::dvec3 t;  // position inside the cell, 0 at the lower corner and 1 at the upper one
  for (int axis = 0; axis < 3; ++axis) {
    const double u = (p[axis] - grid.origin[axis]) / h;
    const double c = std::clamp(std::floor(u), 0.0, lastCell);
    cell[axis] = int(c);
    t[axis] = std::clamp(u - c, 0.0, 1.0);
  }
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 offset((corner >> 0) & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    double w = 1.0;
    for (int axis = 0; axis < 3; ++axis) w *= offset[axis] ? t[axis] : 1.0 - t[axis];
    if (w == 0.0) continue;
    const glm::ivec3 vertex = cell + offset;
    visit(vertex, w, grid.vertexPosition(level, vertex));
  }
}

}  // namespace lgh
