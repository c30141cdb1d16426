#pragma once

// The CPU oracle: lighting at one point from all input lights (exact) or from the hierarchy
// (blended levels). The GPU light pass computes the same sum fragment by fragment.

#include <cstddef>
#include <glm/vec3.hpp>
#include <vector>

#include "lgh/hierarchy.h"
#include "lgh/light.h"

namespace lgh {

struct EvalOptions {
  double alpha = 1.0;          // R_l = alpha h_l: larger is more accurate and visits more lights
  double clampDistance = 0.0;  // dc in lightContribution
  // Finest level blended: 1 (S1, the renderer's default) or 0 (the input lights themselves, with
  // radius R_0 = alpha h_1 / 2). Clamped to [0, L].
  int firstLevel = 1;
};

struct EvalStats {
  size_t lightsVisited = 0;  // lights with non-zero blending weight, summed over calls
};

// Sum over S0 of lightContribution (weight 1 each). `stats` (optional) counts every light.
glm::dvec3 evaluateExact(const std::vector<Light>& lights, const glm::dvec3& x, const glm::dvec3* nx,
                         const EvalOptions& options, EvalStats* stats = nullptr);

// Sum over levels firstLevel..L (level 0 being `lights`, which must be the hierarchy's input) of
// blendWeight(levelRole(l, firstLevel, L), d, R_l) * lightContribution(...).
//
// Brute force is the one-level case of the same rule: when firstLevel == L the single level takes the
// role Only (weight 1). A hierarchy built on a grid with levels == 0 therefore evaluates S0 exactly
// (firstLevel is clamped to 0); with L >= 1 and firstLevel == L it sums the top level alone.
glm::dvec3 evaluateHierarchy(const Hierarchy& hierarchy, const std::vector<Light>& lights, const glm::dvec3& x,
                             const glm::dvec3* nx, const EvalOptions& options, EvalStats* stats = nullptr);

}  // namespace lgh
