#include "lgh/evaluate.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "lgh/shading.h"
#include "test_lights.h"

namespace lgh {
namespace {

using test::kEMin;

// A set of shading points (with optional surface normals) and the exact lighting at each.
struct Probe {
  std::vector<glm::dvec3> points, normals;
  std::vector<glm::dvec3> exact;

  const glm::dvec3* normal(size_t i) const { return normals.empty() ? nullptr : &normals[i]; }
};

Probe makeProbe(const std::vector<Light>& lights, std::vector<glm::dvec3> points, std::vector<glm::dvec3> normals,
                const EvalOptions& options) {
  Probe probe{std::move(points), std::move(normals), {}};
  for (size_t i = 0; i < probe.points.size(); ++i)
    probe.exact.push_back(evaluateExact(lights, probe.points[i], probe.normal(i), options));
  return probe;
}

struct Accuracy {
  double relRms = 0.0;          // sqrt(mean((A - E)²)) / mean(E), on luminance
  double lightsPerQuery = 0.0;  // lights with non-zero blending weight
};

Accuracy measure(const Hierarchy& h, const std::vector<Light>& lights, const Probe& probe, const EvalOptions& options) {
  double squaredError = 0.0, exactSum = 0.0;
  EvalStats stats;
  for (size_t i = 0; i < probe.points.size(); ++i) {
    const glm::dvec3 approx = evaluateHierarchy(h, lights, probe.points[i], probe.normal(i), options, &stats);
    const double error = luminance(approx) - luminance(probe.exact[i]);
    squaredError += error * error;
    exactSum += luminance(probe.exact[i]);
  }
  const double n = double(probe.points.size());
  return {std::sqrt(squaredError / n) / (exactSum / n), double(stats.lightsVisited) / n};
}

// Brute force is the one-level case: a grid with no levels leaves S0 alone, with weight 1.
TEST(Evaluate, ErrorIsZeroWithOneLevelBruteForce) {
  const std::vector<Light> lights = test::randomCube(3000, 1, true);
  const Hierarchy h = buildGather(lights, makeGrid(lights, 0, kEMin));
  ASSERT_EQ(h.levels.size(), 1u);
  const auto points = test::randomPoints(200, 2, glm::dvec3(0.0), glm::dvec3(1.0), 0.2);
  std::mt19937_64 rng(3);
  for (const glm::dvec3& x : points) {
    const glm::dvec3 nx = test::randomUnitVector(rng);
    for (int firstLevel : {0, 1}) {
      const EvalOptions options{1.0, 0.01, firstLevel};
      EvalStats stats;
      const glm::dvec3 exact = evaluateExact(lights, x, &nx, options);
      const glm::dvec3 approx = evaluateHierarchy(h, lights, x, &nx, options, &stats);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(approx[c], exact[c], 1e-12 * exact[c]);
      EXPECT_EQ(stats.lightsVisited, lights.size());
    }
  }
}

// With firstLevel == L the top level alone is used, with weight 1 (the role Only).
TEST(Evaluate, TopLevelAloneIsBruteForceOverIt) {
  const std::vector<Light> lights = test::randomCube(1000, 4, false);
  const Hierarchy h = buildGather(lights, makeGrid(lights, 3, kEMin));
  const glm::dvec3 x(0.3, 0.6, 0.1);
  glm::dvec3 expected(0.0);
  for (const GridLight& g : h.levels[3])
    expected += lightContribution(g.position, g.intensity, g.meanNormal, g.omniFraction, x, nullptr, 0.01);
  const glm::dvec3 actual = evaluateHierarchy(h, lights, x, nullptr, EvalOptions{1.0, 0.01, 3});
  EXPECT_NEAR(actual.x, expected.x, 1e-12 * expected.x);
}

// Far from the lights only the top level answers; it carries all the energy at the lights' centre of
// importance, so the error falls off like (H/d)².
TEST(Evaluate, FarFieldMatchesTheExactSum) {
  const std::vector<Light> lights = test::randomCube(5000, 5, false);
  const Hierarchy h = buildGather(lights, makeGrid(lights, chooseLevelCount(lights, kEMin), kEMin));
  for (const glm::dvec3& x : {glm::dvec3(1000.0, 0.0, 0.0), glm::dvec3(-300.0, 700.0, 50.0)}) {
    const double exact = evaluateExact(lights, x, nullptr, {}).x;
    const double approx = evaluateHierarchy(h, lights, x, nullptr, {}).x;
    EXPECT_NEAR(approx, exact, 1e-5 * exact);
  }
}

// docs/design.md §7's yardstick: 10K omni lights in the unit cube, grey U[0.5, 2], clamp 0.01, 2,000
// points in the cube, relRMS against the exact sum. The authors' cyLightingGrid blends S0 as its finest
// level, as firstLevel = 0 does here, and measured (relRMS, lights per query):
//   alpha 1: 0.046, 127    alpha 2: 0.0074, 703    alpha 4: 0.0011, 3,325.
//
// Why alpha 1 is not held to 0.046: below its top level, cyLightingGrid resolves all 8 "trilinear"
// corners of a light to the same node (its node ids are built from the cell index alone), so its lower
// levels are box clusters: each light lands whole in one node, and a cluster spans one cell (RMS extent
// h/sqrt(12) per axis) where a trilinear splat spans two (h/sqrt(6)). Emulating exactly that (box
// clusters under a trilinear top level, 4 levels for 10K lights) reproduces its lights per query
// (128, 702, 3,326) and errors (0.040, 0.0074, 0.0011) on this set. Tighter clusters win when they are
// used closest, at small alpha; the price is popping when a light crosses a cell, which trilinear
// splatting (the paper's method, and ours) avoids. With trilinear splats alpha 1 gives 0.057-0.060 for
// any level count from 4 to 7, so the bound at alpha 1 guards our own number. From alpha 2 up, the
// reference (scatter) build beats the yardstick outright with fewer lights per query.
//
// firstLevel = 1 (S1 finest, the renderer's default) is printed beside it: near a light it shades with
// S1 clusters instead of the lights themselves, so its error levels off (about 0.08 here) instead of
// vanishing as alpha grows.
TEST(Evaluate, AccuracyImprovesWithAlphaAgainstTheYardstick) {
  const std::vector<Light> lights = test::randomCube(10000, 6, false);
  const GridGeometry grid = makeGrid(lights, chooseLevelCount(lights, kEMin), kEMin);
  const Hierarchy gather = buildGather(lights, grid), scatter = buildScatter(lights, grid);
  const Probe probe =
      makeProbe(lights, test::randomPoints(2000, 7, glm::dvec3(0.0), glm::dvec3(1.0)), {}, EvalOptions{1.0, 0.01, 0});

  struct Row {
    double alpha;
    double gatherBound, scatterBound;  // relRMS bounds with firstLevel = 0
    double yardstickLights;            // cyLightingGrid's lights per query
  };
  const Row rows[] = {
      {0.5, 0.30, 0.22, 0.0},  // not measured by the yardstick
      {1.0, 0.072, 0.065, 127.0},
      {2.0, 0.0085, 0.0074, 703.0},   // scatter: the yardstick's 0.0074
      {4.0, 0.0013, 0.0011, 3325.0},  // scatter: the yardstick's 0.0011
  };
  std::printf("10K omni lights, L = %d, 2000 points: relRMS (lights per query)\n", grid.levels);
  std::printf("alpha | S0 finest, gather  | S0 finest, scatter | S1 finest, gather  | S1 finest, scatter\n");
  Accuracy previous[4];
  for (const Row& row : rows) {
    Accuracy results[4];  // columns as printed
    int column = 0;
    for (int firstLevel : {0, 1})
      for (const Hierarchy* h : {&gather, &scatter})
        results[column++] = measure(*h, lights, probe, EvalOptions{row.alpha, 0.01, firstLevel});
    std::printf("%5.1f", row.alpha);
    for (const Accuracy& a : results) std::printf(" | %8.5f (%6.0f)", a.relRms, a.lightsPerQuery);
    std::printf("\n");

    SCOPED_TRACE("alpha " + std::to_string(row.alpha));
    if (row.alpha > 0.5) {
      EXPECT_LT(results[0].relRms, previous[0].relRms) << "S0 finest, gather";
      EXPECT_LT(results[1].relRms, previous[1].relRms) << "S0 finest, scatter";
      // S1 finest converges to S1's own error: it may level off but must not grow.
      EXPECT_LT(results[2].relRms, previous[2].relRms * 1.01) << "S1 finest, gather";
      EXPECT_LT(results[3].relRms, previous[3].relRms * 1.01) << "S1 finest, scatter";
    }
    EXPECT_LT(results[0].relRms, row.gatherBound);
    EXPECT_LT(results[1].relRms, row.scatterBound);
    if (row.alpha >= 2.0) {
      EXPECT_LT(results[1].lightsPerQuery, row.yardstickLights) << "more lights per query than the yardstick";
    }
    std::copy(results, results + 4, previous);
  }
}

// Oriented lights seen from oriented surfaces exercise the emission lobe of the clusters.
TEST(Evaluate, AccuracyImprovesWithAlphaForOrientedLights) {
  const std::vector<Light> lights = test::randomCube(10000, 8, true);
  const GridGeometry grid = makeGrid(lights, chooseLevelCount(lights, kEMin), kEMin);
  const Hierarchy gather = buildGather(lights, grid);
  std::mt19937_64 rng(9);
  std::vector<glm::dvec3> normals(1000);
  for (glm::dvec3& n : normals) n = test::randomUnitVector(rng);
  const Probe probe = makeProbe(lights, test::randomPoints(1000, 10, glm::dvec3(0.0), glm::dvec3(1.0), 0.1), normals,
                                EvalOptions{1.0, 0.01, 0});
  std::printf("10K oriented lights, L = %d, 1000 oriented points; relRMS (lights per query)\n", grid.levels);
  std::printf("alpha | S0 finest, gather | S1 finest, gather\n");
  double previous[2] = {1e30, 1e30};
  for (double alpha : {0.5, 1.0, 2.0, 4.0}) {
    std::printf("%5.1f", alpha);
    for (int firstLevel : {0, 1}) {
      const Accuracy a = measure(gather, lights, probe, EvalOptions{alpha, 0.01, firstLevel});
      std::printf(" | %8.5f (%6.0f)", a.relRms, a.lightsPerQuery);
      // S1 finest converges to S1's own error: it may level off but must not grow.
      const double tolerance = firstLevel == 0 ? 1.0 : 1.01;
      EXPECT_LT(a.relRms, previous[firstLevel] * tolerance) << "alpha " << alpha << ", first level " << firstLevel;
      previous[firstLevel] = a.relRms;
    }
    std::printf("\n");
  }
}

// docs/design.md §8: every extreme set, both builds, alpha from 0.25 to 16 and levels from 1 to the
// maximum evaluate to finite, non-negative light; at alpha 16 with S0 finest every cluster is used at
// 16 times its size or farther, so the hierarchy stays close to the exact sum.
TEST(Evaluate, ExtremesStayFiniteAndConverge) {
  for (const auto& [name, lights] : test::extremeSets()) {
    const GridGeometry bounds = makeGrid(lights, 1, kEMin);
    const auto points =
        test::randomPoints(30, 11, bounds.origin, bounds.origin + bounds.topCellSize, 0.5 * bounds.topCellSize);
    // 2,000 coincident VPLs with random normals seen from afar are one cluster whatever alpha is:
    // what remains is the emission lobe's error (a cosine plus a constant cannot be 2,000 distinct
    // cosine lobes; about 4% here), not the hierarchy's.
    const double convergenceBound = name == "all lights at one point" ? 0.05 : 0.01;
    for (int levels : {1, chooseLevelCount(lights, kEMin), kMaxLevels}) {
      const GridGeometry grid = makeGrid(lights, levels, kEMin);
      for (const Hierarchy& h : {buildScatter(lights, grid), buildGather(lights, grid)}) {
        for (double alpha : {0.25, 1.0, 16.0}) {
          for (int firstLevel : {0, 1}) {
            for (double clamp : {0.0, 0.01}) {
              SCOPED_TRACE(name + ", L " + std::to_string(levels) + ", alpha " + std::to_string(alpha) +
                           ", first level " + std::to_string(firstLevel));
              const EvalOptions options{alpha, clamp, firstLevel};
              double squaredError = 0.0, exactSum = 0.0;
              for (const glm::dvec3& x : points) {
                const glm::dvec3 value = evaluateHierarchy(h, lights, x, nullptr, options);
                ASSERT_TRUE(test::isFinite(value));
                ASSERT_GE(glm::min(value.x, glm::min(value.y, value.z)), 0.0);
                const double exact = luminance(evaluateExact(lights, x, nullptr, options));
                squaredError += (luminance(value) - exact) * (luminance(value) - exact);
                exactSum += exact;
              }
              if (exactSum == 0.0) {
                EXPECT_EQ(squaredError, 0.0);
              } else if (alpha == 16.0 && firstLevel == 0) {
                const double n = double(points.size());
                EXPECT_LT(std::sqrt(squaredError / n) / (exactSum / n), convergenceBound);
              }
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace lgh
