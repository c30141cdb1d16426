#pragma once

// The light tree of real-time stochastic lightcuts (Lin & Yuksel 2020, Real-Time Stochastic Lightcuts,
// §3.1-3.3, Eq. 1-2): the CPU reference of the GPU build and of the cut selection and sampling
// probabilities. A perfect binary tree over the input lights, Morton-ordered, stored as a 1-based heap.
//
// The build is in float and must match the GPU build (render/, glsl/shared/light_tree_types.h) bit for
// bit, so its operations are written in a fixed order (docs/design.md §12). Traversal and cuts are in
// double: the GPU follows the same math in float and is compared with them statistically.

#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "lgh/light.h"

namespace lgh {

inline constexpr uint32_t kTreeNoLight = 0xffffffffu;  // lightIndex of internal nodes and padding leaves
inline constexpr int kMortonLevels = 1024;             // cells per axis: 10 bits each, 30-bit codes

// Matches the GPU node field for field. An empty node (no lit light below) has intensity 0 and the
// inverted box (+FLT_MAX, -FLT_MAX), which min / max merge away.
struct LightTreeNode {
  glm::vec3 boundMin;  // box of the lit lights' positions below
  float intensity;     // sum of lightTreeIntensity over the lights below
  glm::vec3 boundMax;
  uint32_t lightIndex;  // a leaf's index in the input lights; kTreeNoLight for internal and padding nodes
};
static_assert(sizeof(LightTreeNode) == 32, "the GPU node is 32 bytes");

struct LightTree {
  int levels = 0;          // L = ceil(log2 N) + 1; 1 light: one level, the root is its leaf; no lights: 0
  uint32_t leafCount = 0;  // 2^(L-1), 0 without lights
  // Heap of 2 leafCount nodes: nodes[0] unused (zero), root 1, children of i at 2i and 2i + 1, leaves
  // at [leafCount, 2 leafCount); the first N leaves hold the lights, the rest are empty padding.
  std::vector<LightTreeNode> nodes;
  bool isLeaf(uint32_t node) const { return node >= leafCount; }
};

// The scalar the tree ranks lights by: Rec. 709 luminance, in float and in the GPU's order of operations.
float lightTreeIntensity(const Light& light);

// Levels of the tree over `count` lights: 0 for none, else ceil(log2 count) + 1.
int lightTreeLevels(size_t count);

// 30-bit Morton code of p in the box [lower, upper] (p inside it): each axis quantised to 1024 cells
// (0 on an axis of zero extent, the upper face in cell 1023), x in the highest of each three bits.
uint32_t mortonCode(const glm::vec3& p, const glm::vec3& lower, const glm::vec3& upper);

// The tree over `lights`: leaves in (Morton code, index) order, dark lights as leaves of intensity 0 and
// an empty box, internal nodes the sums and unions of their children. No lights: an empty tree.
// Throws std::invalid_argument for invalid lights (requireValidLights).
LightTree buildLightTree(const std::vector<Light>& lights);

// Probability of descending from internal `node` to its first child 2 node at the point x with unit
// normal n (Eq. 1-2: the mean of the closest- and farthest-point importance ratios, distances floored at
// the shading's clamp distance d_c), or nullopt for a dead branch (both children dark, or both behind the
// tangent plane of x).
std::optional<double> firstChildProbability(const LightTree& tree, uint32_t node, const glm::dvec3& x,
                                            const glm::dvec3& n, double clampDistance = 0.0);

// Probability of reaching each leaf below `node` from it, leaf (node << depth) + i at index i: the product
// of the child probabilities along the path, 0 below a dead branch. Sums to 1 unless a dead branch is met.
std::vector<double> leafProbabilities(const LightTree& tree, uint32_t node, const glm::dvec3& x, const glm::dvec3& n,
                                      double clampDistance = 0.0);

// Upper bound of `node`'s contribution at (x, n), the authors' errorFunction: 0 for a leaf, else
// I F(B) / max(dMin²(B), minDistance²), with F the cosine bound of the node's box B. minDistance is
// errorLimit times the diagonal of the lights' box, and at least the shading's clamp distance d_c.
double cutErrorBound(const LightTree& tree, uint32_t node, const glm::dvec3& x, const glm::dvec3& n,
                     double minDistance);

// The greedy cut of at most maxNodes (1..32) nodes, in the order the GPU keeps them: start from the root,
// split the node of largest error until the cut is full or no error is positive. Empty for an empty tree.
// Throws std::invalid_argument for maxNodes outside [1, 32].
std::vector<uint32_t> selectCut(const LightTree& tree, const glm::dvec3& x, const glm::dvec3& n, int maxNodes,
                                double minDistance);

}  // namespace lgh
