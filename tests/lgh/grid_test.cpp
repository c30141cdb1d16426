#include "lgh/grid.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>

#include "lgh/hierarchy.h"
#include "test_lights.h"

namespace lgh {
namespace {

using test::kEMin;

TEST(Grid, TopCellIsCentredOnTheLightBoundsWithOnePercentMargin) {
  const std::vector<Light> lights = {
      {glm::vec3(-1.0f, 2.0f, 0.0f), glm::vec3(1.0f)},
      {glm::vec3(3.0f, 2.5f, 1.0f), glm::vec3(1.0f)},
  };
  const GridGeometry grid = makeGrid(lights, 4, kEMin);
  EXPECT_DOUBLE_EQ(grid.topCellSize, 1.01 * 4.0);
  const glm::dvec3 centre = grid.origin + 0.5 * grid.topCellSize;
  EXPECT_DOUBLE_EQ(centre.x, 1.0);
  EXPECT_DOUBLE_EQ(centre.y, 2.25);
  EXPECT_DOUBLE_EQ(centre.z, 0.5);
}

TEST(Grid, CellSizesHalveFromTheTopDown) {
  GridGeometry grid;
  grid.topCellSize = 3.0;
  grid.levels = 5;
  for (int level = 1; level <= 5; ++level) {
    EXPECT_DOUBLE_EQ(grid.cellSize(level), 3.0 / double(1 << (5 - level)));
    EXPECT_EQ(grid.cellsPerAxis(level), 1 << (5 - level));
    EXPECT_DOUBLE_EQ(grid.radius(level, 1.5), 1.5 * grid.cellSize(level));
  }
  EXPECT_DOUBLE_EQ(grid.cellSize(0), 0.5 * grid.cellSize(1));
}

TEST(Grid, DarkLightsDoNotStretchTheGrid) {
  std::vector<Light> lights = test::randomCube(100, 1, false);
  lights.push_back({glm::vec3(1000.0f), glm::vec3(0.0f)});
  const GridGeometry grid = makeGrid(lights, 3, kEMin);
  EXPECT_LT(grid.topCellSize, 1.01 * std::sqrt(3.0));

  // Only dark lights: the grid still covers them.
  const std::vector<Light> dark = {{glm::vec3(0.0f), glm::vec3(0.0f)}, {glm::vec3(2.0f), glm::vec3(0.0f)}};
  EXPECT_DOUBLE_EQ(makeGrid(dark, 1, kEMin).topCellSize, 1.01 * 2.0);
}

TEST(Grid, DegenerateBoundsUseEMin) {
  const GridGeometry none = makeGrid({}, 3, 0.5);
  EXPECT_EQ(none.origin, glm::dvec3(0.0));
  EXPECT_DOUBLE_EQ(none.topCellSize, 1.01 * 0.5);

  const std::vector<Light> one = {{glm::vec3(5.0f, 6.0f, 7.0f), glm::vec3(1.0f)}};
  const GridGeometry grid = makeGrid(one, 3, 0.5);
  EXPECT_DOUBLE_EQ(grid.topCellSize, 1.01 * 0.5);
  EXPECT_DOUBLE_EQ(grid.origin.x + 0.5 * grid.topCellSize, 5.0);

  // eMin = 0 with coincident lights must still give a usable cell.
  EXPECT_GT(makeGrid(one, 3, 0.0).topCellSize, 0.0);
}

TEST(Grid, RejectsInvalidLightsAndLevels) {
  std::vector<Light> lights = test::randomCube(10, 2, true);
  EXPECT_EQ(validateLights(lights), "");
  EXPECT_THROW(makeGrid(lights, -1, kEMin), std::invalid_argument);
  EXPECT_THROW(makeGrid(lights, kMaxLevels + 1, kEMin), std::invalid_argument);
  EXPECT_THROW(makeGrid(lights, 3, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(chooseLevelCount(lights, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);

  struct Case {
    int index;
    Light light;
    const char* problem;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const Case cases[] = {
      {3, {glm::vec3(nan, 0.0f, 0.0f), glm::vec3(1.0f)}, "non-finite position"},
      {4, {glm::vec3(0.0f), glm::vec3(1.0f, inf, 1.0f)}, "non-finite intensity"},
      {5, {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.0f, nan, 1.0f)}, "non-finite normal"},
      {6, {glm::vec3(0.0f), glm::vec3(1.0f, -1e-3f, 1.0f)}, "negative intensity"},
      {7, {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.0f, 0.0f, 2.0f)}, "normal is neither zero nor unit length"},
  };
  for (const Case& c : cases) {
    std::vector<Light> bad = lights;
    bad[c.index] = c.light;
    EXPECT_EQ(validateLights(bad), "light " + std::to_string(c.index) + ": " + c.problem);
    EXPECT_THROW(makeGrid(bad, 3, kEMin), std::invalid_argument);
    EXPECT_THROW(chooseLevelCount(bad, kEMin), std::invalid_argument);
  }
}

TEST(Grid, VertexKeysRoundTripOverTheFullRange) {
  const int top = 1 << (kMaxLevels - 1);  // level 1 of the deepest grid has coordinates 0..2^20
  for (const glm::ivec3& v : {glm::ivec3(0), glm::ivec3(top), glm::ivec3(top, 0, 1), glm::ivec3(5, top - 1, 77)})
    EXPECT_EQ(unpackVertex(packVertex(v)), v);
  EXPECT_LT(packVertex(glm::ivec3(top, 0, 0)), packVertex(glm::ivec3(0, 1, 0)));
  EXPECT_LT(packVertex(glm::ivec3(top, top, 0)), packVertex(glm::ivec3(0, 0, 1)));
}

// Trilinear splatting is a partition of unity with linear precision: the weights sum to 1 and the
// weighted vertex positions reproduce the point. Both are what make energy and centres exact.
TEST(Grid, CornerWeightsSumToOneAndReproduceThePoint) {
  GridGeometry grid;
  grid.origin = glm::dvec3(-3.0, 1.0, 1e5);
  grid.topCellSize = 2.0;
  grid.levels = 4;
  const auto points = test::randomPoints(1000, 3, grid.origin, grid.origin + grid.topCellSize);
  for (int level = 1; level <= grid.levels; ++level) {
    for (const glm::dvec3& p : points) {
      double weightSum = 0.0;
      glm::dvec3 offsetSum(0.0);
      int corners = 0;
      forEachCorner(grid, level, p, [&](const glm::ivec3& v, double w, const glm::dvec3& vPos) {
        EXPECT_GT(w, 0.0);
        EXPECT_LE(w, 1.0);
        for (int axis = 0; axis < 3; ++axis) {
          EXPECT_GE(v[axis], 0);
          EXPECT_LE(v[axis], grid.cellsPerAxis(level));
        }
        weightSum += w;
        offsetSum += w * (vPos - p);
        ++corners;
      });
      EXPECT_EQ(corners, 8);
      EXPECT_NEAR(weightSum, 1.0, 1e-14);
      EXPECT_NEAR(glm::length(offsetSum), 0.0, 1e-12 * grid.cellSize(level));
    }
  }
}

TEST(Grid, PointsOnVerticesAndFacesSkipZeroWeights) {
  GridGeometry grid;
  grid.topCellSize = 4.0;
  grid.levels = 3;  // h_1 = 1
  auto count = [&](glm::dvec3 p) {
    int corners = 0;
    forEachCorner(grid, 1, p, [&](const glm::ivec3&, double, const glm::dvec3&) { ++corners; });
    return corners;
  };
  EXPECT_EQ(count(glm::dvec3(1.0, 2.0, 3.0)), 1);
  EXPECT_EQ(count(glm::dvec3(1.5, 2.0, 3.0)), 2);
  EXPECT_EQ(count(glm::dvec3(1.5, 2.5, 3.0)), 4);
  EXPECT_EQ(count(glm::dvec3(4.0, 4.0, 4.0)), 1);  // far corner: the clamped cell keeps it on the grid
}

// The paper's rule, checked against S1 as the build makes it (an independent count).
TEST(Grid, ChooseLevelCountIsTheLastLevelWithFewS1Lights) {
  for (size_t count : {20, 1000, 10000}) {
    for (bool oriented : {false, true}) {
      const std::vector<Light> lights = test::randomCube(count, count + oriented, oriented);
      const int levels = chooseLevelCount(lights, kEMin);
      const size_t s1 = buildGather(lights, makeGrid(lights, levels, kEMin)).levels[1].size();
      const size_t s1Finer = buildGather(lights, makeGrid(lights, levels + 1, kEMin)).levels[1].size();
      SCOPED_TRACE(count);
      if (levels > 1) {  // L = 1 is also the answer when nothing qualifies
        EXPECT_LT(2 * s1, count);
      }
      EXPECT_GE(2 * s1Finer, count);
      EXPECT_EQ(countFinestVertices(lights, makeGrid(lights, levels, kEMin)), s1);
    }
  }
}

TEST(Grid, ChooseLevelCountExtremes) {
  EXPECT_EQ(chooseLevelCount({}, kEMin), 1);
  EXPECT_EQ(chooseLevelCount({{glm::vec3(1.0f), glm::vec3(1.0f)}}, kEMin), 1);
  EXPECT_EQ(chooseLevelCount(test::randomCube(1000, 4, false), kEMin, 2), 2);  // auto would pick 3

  // Coincident lights never fill S1 (at most 8 vertices), so every level qualifies; this must
  // reach kMaxLevels quickly, with memory that follows the 8 occupied vertices.
  std::vector<Light> coincident = test::randomCube(5000, 5, false);
  for (Light& light : coincident) light.position = glm::vec3(0.1f, 0.2f, 0.3f);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(chooseLevelCount(coincident, kEMin), kMaxLevels);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);

  for (const auto& [name, lights] : test::extremeSets()) {
    const int levels = chooseLevelCount(lights, kEMin);
    EXPECT_GE(levels, 1) << name;
    EXPECT_LE(levels, kMaxLevels) << name;
  }
}

}  // namespace
}  // namespace lgh
