#include "lgh/light_tree.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>

namespace lgh {

namespace {

constexpr int kMaxCutNodes = 32;  // the GPU keeps a cut in a fixed array of this size

// Spreads the 10 low bits of v to every third bit: bit b moves to bit 3b.
uint32_t expandBits(uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

// The Morton cell of one coordinate, in float exactly as the GPU computes it.
uint32_t mortonCell(float p, float lower, float upper) {
  const float extent = upper - lower;
  if (!(extent > 0.0f)) return 0;  // all lights share this coordinate
  const float scale = float(kMortonLevels) / extent;
  const float t = (p - lower) * scale;
  if (t >= float(kMortonLevels - 1)) return kMortonLevels - 1;  // the upper face belongs to the last cell
  // t >= 0 for p in the box; the guard only keeps a point outside it (or a NaN) from an undefined conversion.
  return t > 0.0f ? uint32_t(t) : 0u;
}

// A node's box in double, where the traversal math runs.
struct Box {
  glm::dvec3 lower, upper;
  explicit Box(const LightTreeNode& node) : lower(node.boundMin), upper(node.boundMax) {}
  glm::dvec3 closestPoint(const glm::dvec3& x) const { return glm::clamp(x, lower, upper); }
};

double minDistanceSq(const Box& box, const glm::dvec3& x) {
  const glm::dvec3 d = box.closestPoint(x) - x;
  return glm::dot(d, d);
}

double maxDistanceSq(const Box& box, const glm::dvec3& x) {
  double sum = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double d = std::max(std::abs(box.lower[a] - x[a]), std::abs(box.upper[a] - x[a]));
    sum += d * d;
  }
  return sum;
}

// Upper bound of max(0, n·w) over the directions w from x to the box: the largest height above the
// tangent plane over the closest point's distance within it. For a point it is that cosine exactly.
double cosineBound(const Box& box, const glm::dvec3& x, const glm::dvec3& n) {
  double nMax = 0.0;
  for (int a = 0; a < 3; ++a) nMax += std::max(n[a] * (box.lower[a] - x[a]), n[a] * (box.upper[a] - x[a]));
  if (nMax <= 0.0) return 0.0;  // the whole box is behind the tangent plane
  const glm::dvec3 d = box.closestPoint(x) - x;
  const glm::dvec3 tangential = d - glm::dot(d, n) * n;
  return nMax / std::sqrt(glm::dot(tangential, tangential) + nMax * nMax);
}

void requireNode(const LightTree& tree, uint32_t node, bool internal) {
  const size_t end = internal ? tree.leafCount : tree.nodes.size();
  if (node < 1 || node >= end)
    throw std::invalid_argument(internal ? "lgh: light tree node is not an internal node"
                                         : "lgh: light tree node is out of range");
}

}  // namespace

float lightTreeIntensity(const Light& light) {
  // The GPU computes the same expression; neither side may fuse it into FMAs (the x86-64 baseline has none).
  return 0.2126f * light.intensity.r + 0.7152f * light.intensity.g + 0.0722f * light.intensity.b;
}

int lightTreeLevels(size_t count) {
  if (count == 0) return 0;
  int levels = 1;
  while ((size_t(1) << (levels - 1)) < count) ++levels;
  return levels;
}

uint32_t mortonCode(const glm::vec3& p, const glm::vec3& lower, const glm::vec3& upper) {
  return expandBits(mortonCell(p.x, lower.x, upper.x)) << 2 | expandBits(mortonCell(p.y, lower.y, upper.y)) << 1 |
         expandBits(mortonCell(p.z, lower.z, upper.z));
}

LightTree buildLightTree(const std::vector<Light>& lights) {
  requireValidLights(lights);
  if (lights.size() >= kTreeNoLight) throw std::invalid_argument("lgh: too many lights for a light tree");
  LightTree tree;
  tree.levels = lightTreeLevels(lights.size());
  if (tree.levels == 0) return tree;
  tree.leafCount = uint32_t(1) << (tree.levels - 1);
  tree.nodes.assign(2 * size_t(tree.leafCount), LightTreeNode{});  // node 0 stays zero

  // The Morton box spans every light, dark ones included: the GPU reduces positions without reading intensities.
  glm::vec3 lower = lights[0].position, upper = lights[0].position;
  for (const Light& light : lights) {
    lower = glm::min(lower, light.position);
    upper = glm::max(upper, light.position);
  }
  // Sorting the unique keys (code, index) orders the lights exactly as a stable sort by code would.
  std::vector<uint64_t> keys(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) keys[i] = uint64_t(mortonCode(lights[i].position, lower, upper)) << 32 | i;
  std::sort(keys.begin(), keys.end());

  const LightTreeNode empty{glm::vec3(FLT_MAX), 0.0f, glm::vec3(-FLT_MAX), kTreeNoLight};
  for (uint32_t i = 0; i < tree.leafCount; ++i) {
    LightTreeNode& leaf = tree.nodes[tree.leafCount + i];
    leaf = empty;
    if (i >= lights.size()) continue;  // padding up to the power of two
    const uint32_t index = uint32_t(keys[i]);
    leaf.intensity = lightTreeIntensity(lights[index]);
    leaf.lightIndex = index;
    // A dark light keeps its leaf (and index) but no box, so it never stretches its ancestors' bounds.
    if (leaf.intensity > 0.0f) leaf.boundMin = leaf.boundMax = lights[index].position;
  }
  for (uint32_t i = tree.leafCount - 1; i >= 1; --i) {
    const LightTreeNode &first = tree.nodes[2 * i], &second = tree.nodes[2 * i + 1];
    tree.nodes[i] = {glm::min(first.boundMin, second.boundMin), first.intensity + second.intensity,
                     glm::max(first.boundMax, second.boundMax), kTreeNoLight};
  }
  return tree;
}

std::optional<double> firstChildProbability(const LightTree& tree, uint32_t node, const glm::dvec3& x,
                                            const glm::dvec3& n, double clampDistance) {
  requireNode(tree, node, true);
  const LightTreeNode &first = tree.nodes[2 * node], &second = tree.nodes[2 * node + 1];
  // A dark child is never taken; its box is empty, so nothing below may look at it.
  const double intensityJ = first.intensity, intensityK = second.intensity;
  if (intensityJ == 0.0 && intensityK == 0.0) return std::nullopt;
  if (intensityJ == 0.0) return 0.0;
  if (intensityK == 0.0) return 1.0;

  const Box boxJ(first), boxK(second);
  const double cosineJ = cosineBound(boxJ, x, n), cosineK = cosineBound(boxK, x, n);
  if (cosineJ == 0.0 && cosineK == 0.0) return std::nullopt;
  if (cosineJ == 0.0) return 0.0;
  if (cosineK == 0.0) return 1.0;

  // Eq. 1-2: child j's share of the importance I F / d², once with d the distance to the closest point
  // of each box and once to the farthest, averaged. The shading clamps the distance at d_c
  // (1 / max(d², d_c²)), so the importance does too: within d_c of both boxes the closest-point term is
  // I F alone, not the whole share to the box that holds x. Without a floor (d_c = 0), multiplied out,
  // a zero closest distance on one side gives that side the whole share instead of inf / inf; on both
  // sides (x in both boxes) the term falls back to I F alone.
  const double aJ = intensityJ * cosineJ, aK = intensityK * cosineK;
  const double floorSq = clampDistance * clampDistance;
  const double minJ = std::max(minDistanceSq(boxJ, x), floorSq), minK = std::max(minDistanceSq(boxK, x), floorSq);
  const double maxJ = std::max(maxDistanceSq(boxJ, x), floorSq), maxK = std::max(maxDistanceSq(boxK, x), floorSq);
  const double pMin = minJ == 0.0 && minK == 0.0 ? aJ / (aJ + aK) : minK * aJ / (minK * aJ + minJ * aK);
  // Both farthest distances are > 0: a box of farthest distance 0 is the point x, whose cosine bound is 0.
  const double pMax = maxK * aJ / (maxK * aJ + maxJ * aK);
  return (pMin + pMax) / 2.0;
}

std::vector<double> leafProbabilities(const LightTree& tree, uint32_t node, const glm::dvec3& x, const glm::dvec3& n,
                                      double clampDistance) {
  requireNode(tree, node, false);
  // One level at a time: entry i of the level starting at `first` is node first + i, whose children
  // are entries 2i and 2i + 1 of the next level.
  std::vector<double> probabilities{1.0};
  for (uint32_t first = node; !tree.isLeaf(first); first *= 2) {
    std::vector<double> next(2 * probabilities.size(), 0.0);
    for (size_t i = 0; i < probabilities.size(); ++i) {
      if (probabilities[i] == 0.0) continue;  // never reached: a dark sibling or below a dead branch
      const std::optional<double> p = firstChildProbability(tree, first + uint32_t(i), x, n, clampDistance);
      if (!p) continue;  // dead branch: its leaves keep probability 0
      next[2 * i] = probabilities[i] * *p;
      next[2 * i + 1] = probabilities[i] * (1.0 - *p);
    }
    probabilities = std::move(next);
  }
  return probabilities;
}

double cutErrorBound(const LightTree& tree, uint32_t node, const glm::dvec3& x, const glm::dvec3& n,
                     double minDistance) {
  requireNode(tree, node, false);
  // A leaf's light is sampled exactly, so splitting it gains nothing.
  if (tree.isLeaf(node)) return 0.0;
  const LightTreeNode& treeNode = tree.nodes[node];
  if (treeNode.intensity == 0.0f) return 0.0;  // nothing below emits (and the box is empty)
  const Box box(treeNode);
  const double bound = treeNode.intensity * cosineBound(box, x, n);
  // Behind the tangent plane the bound is 0 even where the distance floor is 0 too (no 0/0).
  if (bound == 0.0) return 0.0;
  // The floor keeps a box that contains or touches x from taking every split with an infinite error.
  return bound / std::max(minDistanceSq(box, x), minDistance * minDistance);
}

std::vector<uint32_t> selectCut(const LightTree& tree, const glm::dvec3& x, const glm::dvec3& n, int maxNodes,
                                double minDistance) {
  if (maxNodes < 1 || maxNodes > kMaxCutNodes) throw std::invalid_argument("lgh: a cut holds 1 to 32 nodes");
  if (tree.levels == 0) return {};
  // The authors start from the root with an infinite error, so an internal root is always split first.
  std::vector<uint32_t> cut{1};
  std::vector<double> errors{tree.isLeaf(1) ? 0.0 : std::numeric_limits<double>::infinity()};
  while (int(cut.size()) < maxNodes) {
    // max_element returns the first of equal maxima: ties go to the earliest node in the cut's order.
    const size_t worst = size_t(std::max_element(errors.begin(), errors.end()) - errors.begin());
    if (errors[worst] <= 0.0) break;
    const uint32_t left = 2 * cut[worst], right = left + 1;
    cut[worst] = left;
    errors[worst] = cutErrorBound(tree, left, x, n, minDistance);
    // A dark right child would only waste a slot; a dark left child keeps its parent's slot instead.
    if (tree.nodes[right].intensity != 0.0f) {
      cut.push_back(right);
      errors.push_back(cutErrorBound(tree, right, x, n, minDistance));
    }
  }
  return cut;
}

}  // namespace lgh
