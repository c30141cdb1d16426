#pragma once

// The lighting grid hierarchy: levels 1..L of grid lights, each level a coarser stand-in for the
// input lights S0 (Lin & Yuksel 2019, Sec. 3.1; docs/design.md §2).
//
// A grid light is what a grid vertex collects from the lights around it, each weighted by its
// trilinear weight w and importance a = lum(I):
//   W = sum w a,  D = sum w a e,  Q = sum w a (var + e⊙e),  I = sum w I,  N = sum w a n,  O = sum w a [omni]
// with e the light's offset from the vertex. It becomes a light at the illumination centre
// v + D/W with the summed intensity I (the trilinear weights of one light sum to 1, so every level
// carries exactly the energy of S0), the luminance-weighted spread of its lights as variance (soft
// shadows), their mean normal N/W (emission lobe) and the share O/W of omni lights in it.
//
// Two builds produce it:
//  * buildScatter splats S0 into every level: the reference.
//  * buildGather splats S0 into S1 only and builds each coarser level from the grid lights of the
//    level below (the paper's fast path; a child enters with its own variance, so the second moments
//    stay exact for the child's centre, but trilinear splatting twice smooths a little more).
// Both accumulate offsets from the vertex rather than absolute positions: Q/W - (D/W)² then cancels
// in numbers of the size of a cell, not of the scene's distance from the origin, which keeps the
// variance meaningful for scenes at 1e5 (and lets the GPU build use fixed point).

#include <cstddef>
#include <glm/vec3.hpp>
#include <vector>

#include "lgh/grid.h"
#include "lgh/light.h"

namespace lgh {

struct GridLight {
  glm::dvec3 position;    // illumination centre v + D/W
  glm::dvec3 intensity;   // I = sum w I (not divided: energy is kept)
  glm::dvec3 variance;    // per axis, >= 0
  glm::dvec3 meanNormal;  // N/W, |m| <= 1 - omniFraction
  double omniFraction;    // O/W in [0, 1]
  glm::ivec3 vertex;      // integer vertex coordinates at its level, each in [0, cellsPerAxis(level)]
};

struct Hierarchy {
  GridGeometry grid;
  // levels[l] for l in 1..L, sorted by packVertex(vertex) so builds compare light by light.
  // levels[0] stays empty: S0 is the caller's light list.
  std::vector<std::vector<GridLight>> levels;

  size_t lightCount() const;  // grid lights over all levels
};

// Both throw std::invalid_argument for invalid lights (validateLights). Memory follows the occupied
// vertices (hash maps), never the 8^L vertices of the full grid.
Hierarchy buildScatter(const std::vector<Light>& lights, const GridGeometry& grid);
Hierarchy buildGather(const std::vector<Light>& lights, const GridGeometry& grid);

}  // namespace lgh
