#include "lgh/light_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>

#include "test_lights.h"

namespace lgh {
namespace {

Light greyLight(glm::vec3 position, float grey) { return Light{position, glm::vec3(grey), glm::vec3(0.0f)}; }

bool isEmpty(const LightTreeNode& node) {
  return node.intensity == 0.0f && node.boundMin == glm::vec3(FLT_MAX) && node.boundMax == glm::vec3(-FLT_MAX);
}

// Whether `node` is `ancestor` or lies in its subtree.
bool isUnder(uint32_t node, uint32_t ancestor) {
  while (node > ancestor) node /= 2;
  return node == ancestor;
}

// Probability of descending from `from` to `node`: the product of the child probabilities along the
// path, multiplied bottom-up (leafProbabilities multiplies top-down, so only rounding may differ).
double pathProbability(const LightTree& tree, uint32_t from, uint32_t node, const glm::dvec3& x, const glm::dvec3& n) {
  double probability = 1.0;
  for (; node > from; node /= 2) {
    const std::optional<double> first = firstChildProbability(tree, node / 2, x, n);
    if (!first) return 0.0;
    probability *= node % 2 == 0 ? *first : 1.0 - *first;
  }
  return probability;
}

// A unit normal within ~37 degrees of +z: every light of z >= 0 is then in front of a receiver at z = -5
// whose x, y lie in [0, 1] (n·(p - x) >= 0.8 * 5 - 0.6 * sqrt(2) > 0).
glm::dvec3 upwardNormal(std::mt19937_64& rng) {
  for (;;) {
    const glm::dvec3 n = test::randomUnitVector(rng);
    if (n.z >= 0.8) return n;
  }
}

// Four lights in two clusters split by x: node 2 holds A = [(-3,0,1), (-1,0,2)] (intensity ~2), node 3
// B = [(2,0,1), (4,1,3)] (intensity ~2.5). x's Morton extent [-3, 4] puts A below cell 512 and B above.
std::vector<Light> twoClusters(float zA = 1.0f) {
  return {greyLight({-3.0f, 0.0f, zA}, 1.0f), greyLight({-1.0f, 0.0f, 2.0f * zA}, 1.0f),
          greyLight({2.0f, 0.0f, 1.0f}, 2.0f), greyLight({4.0f, 1.0f, 3.0f}, 0.5f)};
}

TEST(LightTree, IntensityIsRec709LuminanceInFloat) {
  const glm::vec3 p(0.0f);
  EXPECT_EQ(lightTreeIntensity(Light{p, glm::vec3(1.0f, 0.0f, 0.0f)}), 0.2126f);
  EXPECT_EQ(lightTreeIntensity(Light{p, glm::vec3(0.0f, 1.0f, 0.0f)}), 0.7152f);
  EXPECT_EQ(lightTreeIntensity(Light{p, glm::vec3(0.0f, 0.0f, 1.0f)}), 0.0722f);
  EXPECT_EQ(lightTreeIntensity(Light{p, glm::vec3(0.0f)}), 0.0f);
  EXPECT_NEAR(lightTreeIntensity(Light{p, glm::vec3(2.0f)}), 2.0f, 1e-6f);
  EXPECT_NEAR(lightTreeIntensity(Light{p, glm::vec3(1.0f, 2.0f, 3.0f)}), 0.2126 + 1.4304 + 0.2166, 1e-6);
}

TEST(LightTree, LevelsAreCeilLog2PlusOne) {
  const std::vector<std::pair<size_t, int>> expected = {
      {0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 3}, {5, 4}, {8, 4}, {9, 5}, {1024, 11}, {1025, 12}, {size_t(1) << 31, 32}};
  for (const auto& [count, levels] : expected) EXPECT_EQ(lightTreeLevels(count), levels) << count << " lights";
}

// In the box [0, 1024]^3 a coordinate's cell is its integer part.
const glm::vec3 kLower(0.0f), kUpper(1024.0f);

TEST(LightTree, MortonCodeOfTheBoxCornersAndAxes) {
  EXPECT_EQ(mortonCode(kLower, kLower, kUpper), 0u);
  EXPECT_EQ(mortonCode(kUpper, kLower, kUpper), 0x3fffffffu);
  // Cell 1023 on one axis fills every third bit: x from bit 2, y from bit 1, z from bit 0.
  EXPECT_EQ(mortonCode({1024.0f, 0.0f, 0.0f}, kLower, kUpper), 0x24924924u);
  EXPECT_EQ(mortonCode({0.0f, 1024.0f, 0.0f}, kLower, kUpper), 0x12492492u);
  EXPECT_EQ(mortonCode({0.0f, 0.0f, 1024.0f}, kLower, kUpper), 0x09249249u);
  // The middle of a box not at the origin: cell 512 (bit 9) on each axis, the three highest bits.
  EXPECT_EQ(mortonCode(glm::vec3(0.0f), glm::vec3(-2.0f), glm::vec3(2.0f)), 0x38000000u);

  std::mt19937_64 rng(1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i)
    EXPECT_LT(mortonCode({unit(rng), unit(rng), unit(rng)}, {0, 0, 0}, {1, 1, 1}), 1u << 30);
}

TEST(LightTree, MortonCodeInterleavesXYZFromTheHighBit) {
  EXPECT_EQ(mortonCode({1.5f, 0.0f, 0.0f}, kLower, kUpper), 4u);   // qx = 1: bit 2
  EXPECT_EQ(mortonCode({0.0f, 1.5f, 0.0f}, kLower, kUpper), 2u);   // qy = 1: bit 1
  EXPECT_EQ(mortonCode({0.0f, 0.0f, 1.5f}, kLower, kUpper), 1u);   // qz = 1: bit 0
  EXPECT_EQ(mortonCode({2.5f, 0.0f, 0.0f}, kLower, kUpper), 32u);  // qx = 2: bit 5
  // qx = 0b10 -> bit 5, qy = 0b11 -> bits 4 and 1, qz = 0b01 -> bit 0.
  EXPECT_EQ(mortonCode({2.5f, 3.5f, 1.5f}, kLower, kUpper), 0b110011u);
  EXPECT_EQ(mortonCode({512.0f, 0.0f, 0.0f}, kLower, kUpper), 1u << 29);
  EXPECT_EQ(mortonCode({0.0f, 0.0f, 512.0f}, kLower, kUpper), 1u << 27);
}

TEST(LightTree, MortonCodeClampsTheUpperFaceToCell1023) {
  EXPECT_EQ(mortonCode({1023.0f, 0.0f, 0.0f}, kLower, kUpper), 0x24924924u);
  EXPECT_EQ(mortonCode({1023.9f, 0.0f, 0.0f}, kLower, kUpper), 0x24924924u);
  EXPECT_EQ(mortonCode({1022.99f, 0.0f, 0.0f}, kLower, kUpper), 0x24924920u);  // cell 1022
  // In [0, 1] the upper face maps to t = 1024, clamped; in [0, 3] the scale 1024/3 is inexact.
  EXPECT_EQ(mortonCode({1.0f, 0.0f, 0.0f}, {0, 0, 0}, {1, 1, 1}), 0x24924924u);
  EXPECT_EQ(mortonCode({0.5f, 0.0f, 0.0f}, {0, 0, 0}, {1, 1, 1}), 1u << 29);
  EXPECT_EQ(mortonCode({3.0f, 3.0f, 3.0f}, {0, 0, 0}, {3, 3, 3}), 0x3fffffffu);
}

TEST(LightTree, MortonCodeIsZeroOnAnAxisOfZeroExtent) {
  const glm::vec3 lower(0.0f, 5.0f, 0.0f), upper(1024.0f, 5.0f, 1024.0f);
  EXPECT_EQ(mortonCode(upper, lower, upper), 0x24924924u | 0x09249249u);
  EXPECT_EQ(mortonCode({1.5f, 5.0f, 0.0f}, lower, upper), 4u);
  EXPECT_EQ(mortonCode(glm::vec3(7.0f), glm::vec3(7.0f), glm::vec3(7.0f)), 0u);  // one point: every axis
}

TEST(LightTree, LeavesHoldEveryLightOnceInCodeThenIndexOrder) {
  std::vector<Light> lights = test::randomCube(1000, 7, true);
  for (size_t i = 10; i < lights.size(); i += 10) lights[i].position = lights[i - 1].position;  // equal codes
  for (size_t i = 0; i < lights.size(); i += 13) lights[i].intensity = glm::vec3(0.0f);
  const LightTree tree = buildLightTree(lights);
  ASSERT_EQ(tree.leafCount, 1024u);

  glm::vec3 lower = lights[0].position, upper = lights[0].position;
  for (const Light& light : lights) lower = glm::min(lower, light.position), upper = glm::max(upper, light.position);
  std::vector<int> seen(lights.size(), 0);
  uint64_t previousKey = 0;
  for (uint32_t i = 0; i < tree.leafCount; ++i) {
    const LightTreeNode& leaf = tree.nodes[tree.leafCount + i];
    if (i >= lights.size()) {
      EXPECT_TRUE(isEmpty(leaf)) << "padding leaf " << i;
      EXPECT_EQ(leaf.lightIndex, kTreeNoLight);
      continue;
    }
    ASSERT_LT(leaf.lightIndex, lights.size());
    const Light& light = lights[leaf.lightIndex];
    ++seen[leaf.lightIndex];
    const uint64_t key = uint64_t(mortonCode(light.position, lower, upper)) << 32 | leaf.lightIndex;
    if (i > 0) {
      EXPECT_GT(key, previousKey) << "leaf " << i;
    }
    previousKey = key;
    EXPECT_EQ(leaf.intensity, lightTreeIntensity(light));
    if (leaf.intensity > 0.0f) {
      EXPECT_EQ(leaf.boundMin, light.position);
      EXPECT_EQ(leaf.boundMax, light.position);
    } else {
      EXPECT_TRUE(isEmpty(leaf)) << "dark leaf " << i;
    }
  }
  for (size_t i = 0; i < lights.size(); ++i) EXPECT_EQ(seen[i], 1) << "light " << i;
}

TEST(LightTree, InternalNodesAreSumsAndUnionsOfTheirChildren) {
  for (const auto& [name, lights] : test::extremeSets()) {
    SCOPED_TRACE(name);
    const LightTree tree = buildLightTree(lights);
    if (lights.empty()) continue;
    EXPECT_EQ(tree.nodes[0].intensity, 0.0f);  // unused, zero-initialised
    EXPECT_EQ(tree.nodes[0].boundMin, glm::vec3(0.0f));
    EXPECT_EQ(tree.nodes[0].boundMax, glm::vec3(0.0f));
    EXPECT_EQ(tree.nodes[0].lightIndex, 0u);
    for (uint32_t i = 1; i < tree.leafCount; ++i) {
      const LightTreeNode &node = tree.nodes[i], &first = tree.nodes[2 * i], &second = tree.nodes[2 * i + 1];
      ASSERT_EQ(node.intensity, first.intensity + second.intensity) << "node " << i;
      ASSERT_EQ(node.boundMin, glm::min(first.boundMin, second.boundMin)) << "node " << i;
      ASSERT_EQ(node.boundMax, glm::max(first.boundMax, second.boundMax)) << "node " << i;
      ASSERT_EQ(node.lightIndex, kTreeNoLight) << "node " << i;
      ASSERT_EQ(node.intensity == 0.0f, isEmpty(node)) << "node " << i;
    }
    // The root: every light's intensity and the box of the lit lights.
    double total = 0.0;
    glm::vec3 lower(FLT_MAX), upper(-FLT_MAX);
    for (const Light& light : lights) {
      total += lightTreeIntensity(light);
      if (lightTreeIntensity(light) > 0.0f)
        lower = glm::min(lower, light.position), upper = glm::max(upper, light.position);
    }
    EXPECT_NEAR(tree.nodes[1].intensity, total, 1e-5 * total);
    EXPECT_EQ(tree.nodes[1].boundMin, lower);
    EXPECT_EQ(tree.nodes[1].boundMax, upper);
  }
}

TEST(LightTree, TreeSizesForZeroOneTwoThreeAndPowersOfTwo) {
  const LightTree none = buildLightTree({});
  EXPECT_EQ(none.levels, 0);
  EXPECT_EQ(none.leafCount, 0u);
  EXPECT_TRUE(none.nodes.empty());

  const std::vector<std::pair<size_t, int>> sizes = {{1, 1},  {2, 2},  {3, 3},     {4, 3},    {5, 4},
                                                     {16, 5}, {17, 6}, {1024, 11}, {1025, 12}};
  for (const auto& [count, levels] : sizes) {
    const LightTree tree = buildLightTree(test::randomCube(count, count, true));
    EXPECT_EQ(tree.levels, levels) << count << " lights";
    EXPECT_EQ(tree.leafCount, 1u << (levels - 1)) << count << " lights";
    EXPECT_EQ(tree.nodes.size(), 2 * size_t(tree.leafCount)) << count << " lights";
    EXPECT_TRUE(tree.isLeaf(tree.leafCount) && !tree.isLeaf(tree.leafCount - 1));
  }

  // One light: the root is its leaf.
  const Light one = greyLight({0.3f, -2.0f, 7.0f}, 1.5f);
  const LightTree single = buildLightTree({one});
  ASSERT_EQ(single.nodes.size(), 2u);
  EXPECT_TRUE(single.isLeaf(1));
  EXPECT_EQ(single.nodes[1].lightIndex, 0u);
  EXPECT_EQ(single.nodes[1].intensity, lightTreeIntensity(one));
  EXPECT_EQ(single.nodes[1].boundMin, one.position);
  EXPECT_EQ(single.nodes[1].boundMax, one.position);

  // Three lights: the fourth leaf is padding, so node 3 is a copy of leaf 6 but internal.
  const LightTree three = buildLightTree(test::randomCube(3, 5, false));
  EXPECT_TRUE(isEmpty(three.nodes[7]));
  EXPECT_EQ(three.nodes[7].lightIndex, kTreeNoLight);
  EXPECT_EQ(three.nodes[3].intensity, three.nodes[6].intensity);
  EXPECT_EQ(three.nodes[3].boundMin, three.nodes[6].boundMin);
  EXPECT_EQ(three.nodes[3].boundMax, three.nodes[6].boundMax);
  EXPECT_EQ(three.nodes[3].lightIndex, kTreeNoLight);
}

TEST(LightTree, CoincidentLightsKeepInputOrder) {
  std::vector<Light> lights = test::randomCube(256, 9, true);
  const glm::vec3 point(0.25f, 0.5f, -1.0f);
  for (Light& light : lights) light.position = point;
  const LightTree tree = buildLightTree(lights);
  ASSERT_EQ(tree.levels, 9);
  ASSERT_EQ(tree.leafCount, 256u);
  for (uint32_t i = 0; i < 256; ++i) {
    EXPECT_EQ(tree.nodes[256 + i].lightIndex, i);  // every code is 0: the index decides
    EXPECT_EQ(tree.nodes[256 + i].boundMin, point);
  }
  EXPECT_EQ(tree.nodes[1].boundMin, point);
  EXPECT_EQ(tree.nodes[1].boundMax, point);
}

TEST(LightTree, DarkLightsHaveEmptyBoxesButShapeTheMortonBox) {
  std::vector<Light> dark = test::randomCube(100, 15, false);
  for (Light& light : dark) light.intensity = glm::vec3(0.0f);
  const LightTree darkTree = buildLightTree(dark);
  for (uint32_t i = 1; i < darkTree.nodes.size(); ++i) EXPECT_TRUE(isEmpty(darkTree.nodes[i])) << "node " << i;
  for (uint32_t i = 0; i < dark.size(); ++i) EXPECT_NE(darkTree.nodes[darkTree.leafCount + i].lightIndex, kTreeNoLight);
  // The root is split whatever its bound; its left child stays, its dark right child is not appended.
  EXPECT_EQ(selectCut(darkTree, glm::dvec3(0.5), glm::dvec3(0, 0, 1), 4, 0.1), std::vector<uint32_t>{2});

  // With the dark light at x = 1000 in the Morton box, x = 0.5 and 0.6 fall in cell 0 and keep input
  // order; in a box of the lit lights alone 0.6 would land in cell 1023, after 0.5.
  const std::vector<Light> mixed = {greyLight({0.6f, 0.0f, 0.0f}, 1.0f), greyLight({0.5f, 0.0f, 0.0f}, 1.0f),
                                    greyLight({1000.0f, 0.0f, 0.0f}, 0.0f)};
  const LightTree tree = buildLightTree(mixed);
  EXPECT_EQ(tree.nodes[4].lightIndex, 0u);
  EXPECT_EQ(tree.nodes[5].lightIndex, 1u);
  EXPECT_EQ(tree.nodes[6].lightIndex, 2u);
  EXPECT_TRUE(isEmpty(tree.nodes[6]));
  EXPECT_EQ(tree.nodes[1].boundMin, glm::vec3(0.5f, 0.0f, 0.0f));
  EXPECT_EQ(tree.nodes[1].boundMax, glm::vec3(0.6f, 0.0f, 0.0f));
  EXPECT_EQ(tree.nodes[1].intensity, 2.0f * lightTreeIntensity(mixed[0]));
}

TEST(LightTree, RejectsInvalidLights) {
  std::vector<Light> lights = test::randomCube(10, 3, false);
  lights[4].position.y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(buildLightTree(lights), std::invalid_argument);
  lights[4].position.y = 0.0f;
  lights[7].intensity.g = -1.0f;
  EXPECT_THROW(buildLightTree(lights), std::invalid_argument);
}

// For point lights the cosine bound is the cosine and both distances are the distance, so
// p = (I_j cos_j / d_j^2) / (I_j cos_j / d_j^2 + I_k cos_k / d_k^2).
TEST(LightTree, FirstChildProbabilityOfTwoPointLightsByHand) {
  const std::vector<Light> lights = {greyLight({1.0f, 0.0f, 1.0f}, 1.0f), greyLight({-2.0f, 0.0f, 1.0f}, 2.0f)};
  const LightTree tree = buildLightTree(lights);
  ASSERT_EQ(tree.nodes[2].lightIndex, 1u);  // the smaller x comes first
  const double iJ = lightTreeIntensity(lights[1]), iK = lightTreeIntensity(lights[0]);
  // From the origin with n = +z: light 1 at distance^2 5 and cosine 1/sqrt(5), light 0 at 2 and 1/sqrt(2).
  const double aJ = iJ / std::sqrt(5.0), aK = iK / std::sqrt(2.0);
  const double expected = (aJ / 5.0) / (aJ / 5.0 + aK / 2.0);
  const std::optional<double> p = firstChildProbability(tree, 1, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(*p, expected, 1e-14);
}

TEST(LightTree, FirstChildProbabilityOfTwoBoxesByHand) {
  const LightTree tree = buildLightTree(twoClusters());
  ASSERT_EQ(tree.nodes[2].boundMin, glm::vec3(-3, 0, 1));
  ASSERT_EQ(tree.nodes[2].boundMax, glm::vec3(-1, 0, 2));
  ASSERT_EQ(tree.nodes[3].boundMin, glm::vec3(2, 0, 1));
  ASSERT_EQ(tree.nodes[3].boundMax, glm::vec3(4, 1, 3));
  const double iA = tree.nodes[2].intensity, iB = tree.nodes[3].intensity;
  ASSERT_NEAR(iA, 2.0, 1e-6);
  ASSERT_NEAR(iB, 2.5, 1e-6);
  // From the origin with n = +z:
  //  A: highest point z = 2, closest point (-1,0,1), tangential part (-1,0,0): F = 2 / sqrt(1 + 4);
  //     closest distance^2 1 + 1 = 2, farthest 3^2 + 2^2 = 13.
  //  B: highest point z = 3, closest point (2,0,1), tangential part (2,0,0): F = 3 / sqrt(4 + 9);
  //     closest distance^2 4 + 1 = 5, farthest 4^2 + 1^2 + 3^2 = 26.
  const double aA = iA * 2.0 / std::sqrt(5.0), aB = iB * 3.0 / std::sqrt(13.0);
  const double pMin = (aA / 2.0) / (aA / 2.0 + aB / 5.0);
  const double pMax = (aA / 13.0) / (aA / 13.0 + aB / 26.0);
  ASSERT_GT(std::abs(pMin - pMax), 0.01);  // the two terms differ, so both are checked
  const std::optional<double> p = firstChildProbability(tree, 1, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(*p, (pMin + pMax) / 2.0, 1e-14);
}

// The shading clamps the distance at d_c (1 / max(d^2, d_c^2)), and the importance floors it alike. The
// boxes above with d_c^2 = 4: A's closest distance^2 2 becomes 4, B's 5 stays; the farthest (13, 26) stay.
// With d_c^2 = 30 every distance is floored: both terms are the I F ratio.
TEST(LightTree, FirstChildProbabilityFloorsTheDistancesAtTheClampDistance) {
  const LightTree tree = buildLightTree(twoClusters());
  const double iA = tree.nodes[2].intensity, iB = tree.nodes[3].intensity;
  const double aA = iA * 2.0 / std::sqrt(5.0), aB = iB * 3.0 / std::sqrt(13.0);
  const double pMin = (aA / 4.0) / (aA / 4.0 + aB / 5.0), pMax = (aA / 13.0) / (aA / 13.0 + aB / 26.0);
  const std::optional<double> p = firstChildProbability(tree, 1, glm::dvec3(0.0), glm::dvec3(0, 0, 1), 2.0);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(*p, (pMin + pMax) / 2.0, 1e-14);
  const std::optional<double> flat =
      firstChildProbability(tree, 1, glm::dvec3(0.0), glm::dvec3(0, 0, 1), std::sqrt(30.0));
  ASSERT_TRUE(flat.has_value());
  EXPECT_NEAR(*flat, aA / (aA + aB), 1e-14);
}

TEST(LightTree, FirstChildProbabilityWithTheReceiverInsideBothBoxes) {
  // Lights 0-3 share Morton cell 0 of the box [0, 1024]^3 and keep input order: node 4 = {0, 1} with box
  // [0, 0.25]^3, node 5 = {2, 3} with box [0, 0.5] x [0, 0.25]^2. Light 4 (dark) only spans the Morton box.
  const std::vector<Light> lights = {greyLight({0.0f, 0.0f, 0.0f}, 1.0f), greyLight({0.25f, 0.25f, 0.25f}, 1.0f),
                                     greyLight({0.5f, 0.0f, 0.0f}, 1.0f), greyLight({0.0f, 0.25f, 0.25f}, 3.0f),
                                     greyLight({1024.0f, 1024.0f, 1024.0f}, 0.0f)};
  const LightTree tree = buildLightTree(lights);
  ASSERT_EQ(tree.nodes[4].boundMax, glm::vec3(0.25f));
  ASSERT_EQ(tree.nodes[5].boundMin, glm::vec3(0.0f));
  ASSERT_EQ(tree.nodes[5].boundMax, glm::vec3(0.5f, 0.25f, 0.25f));
  // x in both boxes: both closest distances are 0 and both cosine bounds 1 (nMax = 0.125, no tangential
  // part), so the closest-point term is the intensity ratio; farthest distances^2 3/64 and 11/64.
  const double i4 = tree.nodes[4].intensity, i5 = tree.nodes[5].intensity;
  const double pMin = i4 / (i4 + i5);
  const double pMax = (i4 / 3.0) / (i4 / 3.0 + i5 / 11.0);
  const std::optional<double> p = firstChildProbability(tree, 2, glm::dvec3(0.125), glm::dvec3(0, 0, 1));
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(*p, (pMin + pMax) / 2.0, 1e-14);
}

TEST(LightTree, FirstChildProbabilityDeadAndOneSidedBranches) {
  const glm::dvec3 x(0.0), up(0, 0, 1), down(0, 0, -1);
  // Both children behind the tangent plane, or one behind and one on it: dead.
  const LightTree behind = buildLightTree({greyLight({-1, 0, -1}, 1.0f), greyLight({1, 0, -1}, 1.0f)});
  EXPECT_FALSE(firstChildProbability(behind, 1, x, up).has_value());
  const LightTree onPlane = buildLightTree({greyLight({-1, 0, -1}, 1.0f), greyLight({1, 0, 0}, 1.0f)});
  EXPECT_FALSE(firstChildProbability(onPlane, 1, x, up).has_value());
  // One side behind: all of the probability goes to the other.
  const LightTree split = buildLightTree({greyLight({-1, 0, -1}, 1.0f), greyLight({1, 0, 1}, 1.0f)});
  EXPECT_EQ(firstChildProbability(split, 1, x, up), 0.0);
  EXPECT_EQ(firstChildProbability(split, 1, x, down), 1.0);

  // Both children dark: dead; one dark: the other one, wherever the receiver is.
  const LightTree dark = buildLightTree({greyLight({-1, 0, 1}, 0.0f), greyLight({1, 0, 1}, 0.0f)});
  EXPECT_FALSE(firstChildProbability(dark, 1, x, up).has_value());
  const LightTree firstDark = buildLightTree({greyLight({-1, 0, 1}, 0.0f), greyLight({1, 0, -1}, 1.0f)});
  EXPECT_EQ(firstChildProbability(firstDark, 1, x, up), 0.0);
  const LightTree secondDark = buildLightTree({greyLight({-1, 0, -1}, 1.0f), greyLight({1, 0, 1}, 0.0f)});
  EXPECT_EQ(firstChildProbability(secondDark, 1, x, up), 1.0);
  // A padding sibling is dark too: in a tree of 3 lights node 3 always takes its light.
  const LightTree three = buildLightTree(test::randomCube(3, 2, false));
  EXPECT_EQ(firstChildProbability(three, 3, x, up), 1.0);

  EXPECT_THROW(firstChildProbability(three, 0, x, up), std::invalid_argument);
  EXPECT_THROW(firstChildProbability(three, three.leafCount, x, up), std::invalid_argument);
}

TEST(LightTree, LeafProbabilitiesAreProductsAlongThePathAndSumToOne) {
  std::vector<Light> lights = test::randomCube(300, 21, true);
  for (size_t i = 0; i < lights.size(); i += 7) lights[i].intensity = glm::vec3(0.0f);
  const LightTree tree = buildLightTree(lights);
  ASSERT_EQ(tree.leafCount, 512u);
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const glm::dvec3 x(unit(rng), unit(rng), -5.0), n = upwardNormal(rng);
    for (const Light& light : lights) ASSERT_GT(glm::dot(n, glm::dvec3(light.position) - x), 0.0);

    const std::vector<double> probabilities = leafProbabilities(tree, 1, x, n);
    ASSERT_EQ(probabilities.size(), tree.leafCount);
    double sum = 0.0;
    for (uint32_t i = 0; i < tree.leafCount; ++i) {
      const uint32_t leaf = tree.leafCount + i;
      sum += probabilities[i];
      EXPECT_NEAR(probabilities[i], pathProbability(tree, 1, leaf, x, n), 1e-13 * probabilities[i]) << "leaf " << i;
      if (tree.nodes[leaf].intensity > 0.0f) {
        EXPECT_GT(probabilities[i], 0.0) << "lit leaf " << i;
      } else {
        EXPECT_EQ(probabilities[i], 0.0) << "dark or padding leaf " << i;
      }
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);

    // From node 5 (two levels down, 128 leaves): the same leaves, conditioned on reaching node 5.
    const std::vector<double> fromNode5 = leafProbabilities(tree, 5, x, n);
    ASSERT_EQ(fromNode5.size(), 128u);
    const double reach5 = pathProbability(tree, 1, 5, x, n);
    double sum5 = 0.0;
    for (uint32_t i = 0; i < 128; ++i) {
      sum5 += fromNode5[i];
      EXPECT_NEAR(fromNode5[i] * reach5, probabilities[(5u << 7) + i - tree.leafCount], 1e-13);
    }
    EXPECT_NEAR(sum5, 1.0, 1e-12);
  }
  EXPECT_EQ(leafProbabilities(tree, tree.leafCount + 3, glm::dvec3(0.0), glm::dvec3(0, 0, 1)),
            std::vector<double>{1.0});
}

TEST(LightTree, LeafProbabilitiesAreZeroBelowADeadBranch) {
  // Cluster A moved below z = 0: behind the tangent plane of the origin with n = +z.
  const LightTree tree = buildLightTree(twoClusters(-1.0f));
  const glm::dvec3 x(0.0), up(0, 0, 1);
  const std::vector<double> probabilities = leafProbabilities(tree, 1, x, up);
  ASSERT_EQ(probabilities.size(), 4u);
  EXPECT_EQ(probabilities[0], 0.0);
  EXPECT_EQ(probabilities[1], 0.0);
  EXPECT_GT(probabilities[2], 0.0);
  EXPECT_GT(probabilities[3], 0.0);
  EXPECT_NEAR(probabilities[2] + probabilities[3], 1.0, 1e-15);
  // Below the dead branch A itself (node 2) every leaf is unreachable.
  EXPECT_EQ(leafProbabilities(tree, 2, x, up), std::vector<double>(2, 0.0));
  // Seen from above everything, the whole tree is dead.
  EXPECT_EQ(leafProbabilities(tree, 1, glm::dvec3(0, 0, 10), up), std::vector<double>(4, 0.0));
}

TEST(LightTree, CutErrorBoundOfOneBoxByHand) {
  const LightTree tree = buildLightTree(twoClusters());
  const glm::dvec3 origin(0.0), up(0, 0, 1);
  const double iB = tree.nodes[3].intensity, iRoot = tree.nodes[1].intensity;
  // Box B from the origin: F = 3 / sqrt(13), closest distance^2 5 (see FirstChildProbabilityOfTwoBoxesByHand).
  const double fB = 3.0 / std::sqrt(13.0);
  EXPECT_NEAR(cutErrorBound(tree, 3, origin, up, 1.0), iB * fB / 5.0, 1e-14);
  EXPECT_NEAR(cutErrorBound(tree, 3, origin, up, 3.0), iB * fB / 9.0, 1e-14);  // the floor 3^2 wins
  // Root box [(-3,0,1), (4,1,3)]: closest point (0,0,1) straight above, so F = 1 and distance^2 1.
  EXPECT_NEAR(cutErrorBound(tree, 1, origin, up, 0.5), iRoot, 1e-14);
  // Inside B: distance 0, F = 1 (the box reaches 1 above x, nothing tangential): only the floor remains.
  const glm::dvec3 inside(3.0, 0.5, 2.0);
  EXPECT_NEAR(cutErrorBound(tree, 3, inside, up, 0.5), iB / 0.25, 1e-13);
  EXPECT_EQ(cutErrorBound(tree, 3, inside, up, 0.0), std::numeric_limits<double>::infinity());
  // Behind the tangent plane, a leaf, a dark node: 0.
  EXPECT_EQ(cutErrorBound(tree, 3, origin, glm::dvec3(0, 0, -1), 0.0), 0.0);
  for (uint32_t leaf = 4; leaf < 8; ++leaf) EXPECT_EQ(cutErrorBound(tree, leaf, origin, up, 0.1), 0.0);
  const LightTree five = buildLightTree(test::randomCube(5, 4, false));
  EXPECT_EQ(cutErrorBound(five, 7, origin, up, 0.1), 0.0);  // node 7: padding leaves 14 and 15
  EXPECT_THROW(cutErrorBound(tree, 8, origin, up, 0.1), std::invalid_argument);
}

TEST(LightTree, SelectCutOfOneNodeIsTheRoot) {
  const LightTree tree = buildLightTree(test::randomCube(100, 30, true));
  EXPECT_EQ(selectCut(tree, glm::dvec3(0.5), glm::dvec3(0, 0, 1), 1, 0.01), std::vector<uint32_t>{1});
  const LightTree single = buildLightTree(test::randomCube(1, 31, true));
  EXPECT_EQ(selectCut(single, glm::dvec3(0.5), glm::dvec3(0, 0, 1), 32, 0.01), std::vector<uint32_t>{1});
  EXPECT_TRUE(selectCut(buildLightTree({}), glm::dvec3(0.5), glm::dvec3(0, 0, 1), 32, 0.01).empty());
}

TEST(LightTree, SelectCutSplitsInPlaceAppendsRightChildrenAndBreaksTiesInOrder) {
  // Four equal coincident lights: siblings have equal errors, so the first in the cut's order is split.
  std::vector<Light> lights(4, greyLight({0.0f, 0.0f, 1.0f}, 1.0f));
  const LightTree tree = buildLightTree(lights);
  const glm::dvec3 x(0.0), up(0, 0, 1);
  using Cut = std::vector<uint32_t>;
  EXPECT_EQ(selectCut(tree, x, up, 2, 0.01), (Cut{2, 3}));
  EXPECT_EQ(selectCut(tree, x, up, 3, 0.01), (Cut{4, 3, 5}));
  EXPECT_EQ(selectCut(tree, x, up, 4, 0.01), (Cut{4, 6, 5, 7}));
  EXPECT_EQ(selectCut(tree, x, up, 32, 0.01), (Cut{4, 6, 5, 7}));  // leaves have error 0: done
  // The root is split even when its bound is 0 (behind the plane); its children then stay.
  EXPECT_EQ(selectCut(tree, x, -up, 32, 0.01), (Cut{2, 3}));
}

TEST(LightTree, SelectCutPartitionsTheLitLeaves) {
  std::vector<std::vector<Light>> sets = {test::randomCube(500, 40, true), test::wideIntensities(300, 41),
                                          test::randomCube(37, 42, false)};
  for (size_t i = 0; i < sets[0].size(); i += 5) sets[0][i].intensity = glm::vec3(0.0f);
  std::mt19937_64 rng(43);
  for (const std::vector<Light>& lights : sets) {
    const LightTree tree = buildLightTree(lights);
    const std::vector<glm::dvec3> points = test::randomPoints(10, rng(), glm::dvec3(0.0), glm::dvec3(1.0), 0.5);
    for (const glm::dvec3& x : points) {
      const glm::dvec3 n = test::randomUnitVector(rng);
      for (int maxNodes : {1, 2, 3, 7, 16, 32}) {
        for (double minDistance : {0.0, 0.01, 0.2}) {
          SCOPED_TRACE(testing::Message()
                       << lights.size() << " lights, maxNodes " << maxNodes << ", minDistance " << minDistance);
          const std::vector<uint32_t> cut = selectCut(tree, x, n, maxNodes, minDistance);
          ASSERT_GE(cut.size(), 1u);
          ASSERT_LE(cut.size(), size_t(maxNodes));
          if (maxNodes > 1) {
            EXPECT_NE(cut[0], 1u);  // the root is always split
          }
          for (size_t a = 0; a < cut.size(); ++a) {
            ASSERT_GE(cut[a], 1u);
            ASSERT_LT(cut[a], tree.nodes.size());
            if (tree.nodes[cut[a]].intensity == 0.0f) {
              EXPECT_EQ(cut[a] % 2, 0u) << "dark right child " << cut[a];
            }
            for (size_t b = 0; b < a; ++b) EXPECT_FALSE(isUnder(cut[a], cut[b]) || isUnder(cut[b], cut[a]));
          }
          for (uint32_t leaf = tree.leafCount; leaf < tree.nodes.size(); ++leaf) {
            if (tree.nodes[leaf].intensity == 0.0f) continue;
            const auto covering = std::count_if(cut.begin(), cut.end(), [&](uint32_t c) { return isUnder(leaf, c); });
            ASSERT_EQ(covering, 1) << "leaf " << leaf;
          }
          // The cut stops short only when no node's error is positive.
          if (int(cut.size()) < maxNodes) {
            for (uint32_t node : cut) EXPECT_LE(cutErrorBound(tree, node, x, n, minDistance), 0.0) << "node " << node;
          }
        }
      }
    }
  }
}

TEST(LightTree, SelectCutWithEnoughNodesReachesTheLitLeaves) {
  // All lights at z in [1, 2], in front of a receiver at z = 0 facing +z: every lit node has a positive error.
  const glm::dvec3 x(0.5, 0.5, 0.0), up(0, 0, 1);
  const std::vector<Light> lit = test::randomCube(12, 50, true, glm::dvec3(0.0, 0.0, 1.0));
  const LightTree litTree = buildLightTree(lit);
  std::vector<uint32_t> cut = selectCut(litTree, x, up, 12, 1e-6);
  std::sort(cut.begin(), cut.end());
  std::vector<uint32_t> leaves(12);
  for (uint32_t i = 0; i < 12; ++i) leaves[i] = litTree.leafCount + i;
  EXPECT_EQ(cut, leaves);

  // With dark lights the cut holds every lit leaf itself; what else it holds are dark left children,
  // which take a slot in place of their split parent.
  std::vector<Light> mixed = lit;
  for (size_t i = 0; i < mixed.size(); i += 3) mixed[i].intensity = glm::vec3(0.0f);
  const LightTree mixedTree = buildLightTree(mixed);
  const std::vector<uint32_t> mixedCut = selectCut(mixedTree, x, up, 32, 1e-6);
  size_t litLeaves = 0;
  for (uint32_t node : mixedCut) {
    if (mixedTree.nodes[node].intensity > 0.0f) {
      EXPECT_TRUE(mixedTree.isLeaf(node)) << "node " << node;
      ++litLeaves;
    } else {
      EXPECT_EQ(node % 2, 0u) << "node " << node;
    }
  }
  EXPECT_EQ(litLeaves, 8u);
}

TEST(LightTree, SelectCutRejectsSizesOutside1To32) {
  const LightTree tree = buildLightTree(test::randomCube(10, 60, true));
  for (int maxNodes : {-1, 0, 33})
    EXPECT_THROW(selectCut(tree, glm::dvec3(0.5), glm::dvec3(0, 0, 1), maxNodes, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace lgh
