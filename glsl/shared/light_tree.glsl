// The light tree's traversal math (Lin & Yuksel 2020, "Real-time stochastic lightcuts", §3.2-3.3, Eq. 1-2,
// as the authors' code computes it; docs/design.md §12). Include after a `nodes` buffer of
// GpuLightTreeNode (and, for descendToLeaf, shared/sampling.glsl). The CPU reference of the same math, in
// double, is lgh/light_tree.h.
#ifndef LGH_LIGHT_TREE_GLSL
#define LGH_LIGHT_TREE_GLSL
#include "shared/light_tree_types.h"

// Squared distance from x to the box's closest point (0 inside) and farthest corner.
float closestDistanceSq(vec3 x, vec3 lo, vec3 hi) {
  vec3 d = clamp(x, lo, hi) - x;
  return dot(d, d);
}
float farthestDistanceSq(vec3 x, vec3 lo, vec3 hi) {
  vec3 d = max(abs(lo - x), abs(hi - x));
  return dot(d, d);
}

// A bound of the receiver's cosine over the box (the paper's F: no emitter cone, the authors' GPU tree has
// none): the box's largest extent along n over the hypotenuse with the closest point's tangential offset.
// For a point it is max(0, cos) of the direction to it; 0 when the box lies behind the tangent plane.
float cosineBound(vec3 x, vec3 n, vec3 lo, vec3 hi) {
  vec3 a = n * (lo - x), b = n * (hi - x);
  float normalExtent = max(a.x, b.x) + max(a.y, b.y) + max(a.z, b.z);
  if (!(normalExtent > 0.0)) return 0.0;
  vec3 d = clamp(x, lo, hi) - x;
  vec3 tangential = d - dot(d, n) * n;
  return normalExtent * inversesqrt(dot(tangential, tangential) + normalExtent * normalExtent);
}

// Eq. 2's normalised weight of the first child from its and the second child's squared distances.
float firstOfTwo(float distanceSq0, float distanceSq1, float weighted0, float weighted1) {
  float w0 = distanceSq1 * weighted0, w1 = distanceSq0 * weighted1;
  float sum = w0 + w1;
  return sum > 0.0 ? w0 / sum : weighted0 / (weighted0 + weighted1);
}

// The probability of descending from `node` to its first child 2 node at (x, n): the mean of Eq. 2's
// closest-point and farthest-point probabilities, each from Eq. 1's weights I F / max(d^2, d_c^2) (the
// shading's clamp, so within d_c of both boxes the closest term is I F alone). False for a dead branch
// (neither child can light x); the sample then counts as zero (unbiased: Yuksel 2020, §5).
bool firstChildProbability(uint node, vec3 x, vec3 n, float clampDistance, out float probability) {
  GpuLightTreeNode c0 = nodes[2u * node], c1 = nodes[2u * node + 1u];
  probability = 0.0;
  if (c0.intensity == 0.0) return c1.intensity != 0.0;  // all of it to the second child, or none
  probability = 1.0;
  if (c1.intensity == 0.0) return true;
  float f0 = cosineBound(x, n, c0.boundMin, c0.boundMax), f1 = cosineBound(x, n, c1.boundMin, c1.boundMax);
  if (f0 == 0.0 && f1 == 0.0) return false;
  probability = f1 == 0.0 ? 1.0 : 0.0;
  if (f0 == 0.0 || f1 == 0.0) return true;
  float a0 = c0.intensity * f0, a1 = c1.intensity * f1;
  float floorSq = clampDistance * clampDistance;
  float min0 = max(closestDistanceSq(x, c0.boundMin, c0.boundMax), floorSq);
  float min1 = max(closestDistanceSq(x, c1.boundMin, c1.boundMax), floorSq);
  // Both boxes hold x (without a floor): the closest-point term has no distances to compare.
  float closest = min0 == 0.0 && min1 == 0.0 ? a0 / (a0 + a1) : firstOfTwo(min0, min1, a0, a1);
  float farthest = firstOfTwo(max(farthestDistanceSq(x, c0.boundMin, c0.boundMax), floorSq),
                              max(farthestDistanceSq(x, c1.boundMin, c1.boundMax), floorSq), a0, a1);
  // The uniforms are multiples of 2^-24 (nextFloat): a child whose probability is below that would still be
  // drawn 2^-24 of the time and weighed by 1 / p, an infinite sample (seen: 816 NaN pixels in a filtered
  // Sponza frame), and one that rounds to 0 would never be drawn although it can light x. So the
  // probability is rounded to the uniforms' steps, at least one step from 0 and 1: the probability a
  // descent reports is then exactly the one it was drawn with, and both children stay reachable.
  const float kSteps = 16777216.0;  // 2^24
  probability = clamp(round(0.5 * (closest + farthest) * kSteps), 1.0, kSteps - 1.0) / kSteps;
  return true;
}

// The cut's error bound of a node at (x, n) (the authors' errorFunction): I F / max(d_min^2, minDistance^2);
// 0 for a leaf, which cannot be split.
float cutErrorBound(uint node, uint leafCount, vec3 x, vec3 n, float minDistance) {
  if (node >= leafCount) return 0.0;
  GpuLightTreeNode c = nodes[node];
  if (c.intensity == 0.0) return 0.0;
  float f = cosineBound(x, n, c.boundMin, c.boundMax);
  if (f == 0.0) return 0.0;  // behind the tangent plane (and 0, not 0 / 0, where x is in the box without a floor)
  return c.intensity * f / max(closestDistanceSq(x, c.boundMin, c.boundMax), minDistance * minDistance);
}

// One leaf drawn under `node` at (x, n) by firstChildProbability, and the probability of drawing it; 0 for a
// dead branch. A fresh uniform per level (the authors rescale one uniform down the tree, which spends its
// mantissa over 17-21 levels): the same distribution. A leaf may be dark (a padding leaf under a lit node
// is never drawn: its probability is 0).
uint descendToLeaf(uint node, uint leafCount, vec3 x, vec3 n, float clampDistance, inout Rng rng,
                   out float probability) {
  probability = 1.0;
  while (node < leafCount) {
    float first;
    if (!firstChildProbability(node, x, n, clampDistance, first)) return 0u;
    bool takeFirst = nextFloat(rng) < first;
    probability *= takeFirst ? first : 1.0 - first;
    node = 2u * node + (takeFirst ? 0u : 1u);
  }
  return node;
}
#endif
