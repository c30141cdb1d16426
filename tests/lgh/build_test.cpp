#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <stdexcept>
#include <unordered_map>

#include "lgh/hierarchy.h"
#include "test_lights.h"

namespace lgh {
namespace {

using test::kEMin;

using Build = std::function<Hierarchy(const std::vector<Light>&, const GridGeometry&)>;
const std::pair<const char*, Build> kBuilds[] = {{"scatter", buildScatter}, {"gather", buildGather}};

// Luminance-weighted moments of a set of (cluster) lights about a point z. Splatting with weights
// that sum to 1 and reproduce positions (grid_test) conserves all of them, on every level and for
// both builds: total intensity (energy), importance, centre of importance, second moment (cluster
// variance + spread of the centres), normal sum and omni share. A wrong D, Q, N or O sum, or a wrong
// finalisation, breaks one of them.
struct Moments {
  glm::dvec3 intensity{0.0};
  double importance = 0.0;
  glm::dvec3 first{0.0}, second{0.0}, normal{0.0};
  double omni = 0.0;

  void add(const glm::dvec3& I, const glm::dvec3& c, const glm::dvec3& var, const glm::dvec3& n, double o,
           const glm::dvec3& z) {
    const double a = luminance(I);
    intensity += I;
    importance += a;
    first += a * (c - z);
    second += a * (var + (c - z) * (c - z));
    normal += a * n;
    omni += a * o;
  }
};

Moments momentsOf(const std::vector<Light>& lights, const glm::dvec3& z) {
  Moments m;
  for (const Light& l : lights)
    m.add(glm::dvec3(l.intensity), glm::dvec3(l.position), glm::dvec3(0.0), unitNormal(l), omniFraction(l), z);
  return m;
}

Moments momentsOf(const std::vector<GridLight>& lights, const glm::dvec3& z) {
  Moments m;
  for (const GridLight& l : lights) m.add(l.intensity, l.position, l.variance, l.meanNormal, l.omniFraction, z);
  return m;
}

// Double sums over up to 1e5 lights stay far inside this; the brief's bound for energy is 1e-5.
constexpr double kRelTol = 1e-9;

void expectMomentsConserved(const Hierarchy& h, const std::vector<Light>& lights) {
  const double H = h.grid.topCellSize;
  const glm::dvec3 z = h.grid.origin + 0.5 * H;
  const Moments input = momentsOf(lights, z);
  for (int level = 1; level <= h.grid.levels; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    const Moments m = momentsOf(h.levels[level], z);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(m.intensity[c], input.intensity[c], kRelTol * input.intensity[c]) << "energy, channel " << c;
      EXPECT_NEAR(m.first[c], input.first[c], kRelTol * input.importance * H) << "centre, axis " << c;
      EXPECT_NEAR(m.second[c], input.second[c], kRelTol * input.importance * H * H) << "second moment";
      EXPECT_NEAR(m.normal[c], input.normal[c], kRelTol * input.importance) << "normal sum";
    }
    EXPECT_NEAR(m.importance, input.importance, kRelTol * input.importance);
    EXPECT_NEAR(m.omni, input.omni, kRelTol * input.importance) << "omni share";
  }
}

// What is wrong with one grid light of `level`, or "" if it is well formed: finite, within one cell of
// its vertex (the centre of lights that all lie within a cell of it), variance within that reach.
std::string problemWith(const GridLight& light, const GridGeometry& grid, int level) {
  if (!(test::isFinite(light.position) && test::isFinite(light.intensity) && test::isFinite(light.variance) &&
        test::isFinite(light.meanNormal) && std::isfinite(light.omniFraction)))
    return "non-finite field";
  const double cell = grid.cellSize(level);
  const glm::dvec3 vertexPos = grid.vertexPosition(level, light.vertex);
  for (int axis = 0; axis < 3; ++axis) {
    if (light.vertex[axis] < 0 || light.vertex[axis] > grid.cellsPerAxis(level)) return "vertex outside the grid";
    // Vertex positions carry the rounding of their magnitude, which matters when a tiny cell
    // (eMin-sized top cell, 21 levels) sits far from the origin.
    const double reach = cell * (1.0 + 1e-9) + 1e-14 * (std::abs(vertexPos[axis]) + grid.topCellSize);
    if (std::abs(light.position[axis] - vertexPos[axis]) > reach) return "centre more than a cell from its vertex";
    if (light.variance[axis] < 0.0) return "negative variance";
    if (light.variance[axis] > reach * reach) return "variance wider than a cell";
  }
  if (!(luminance(light.intensity) > 0.0)) return "dark grid light";
  if (glm::length(light.meanNormal) > 1.0 + 1e-12) return "|mean normal| > 1";
  if (light.omniFraction < 0.0 || light.omniFraction > 1.0) return "omni fraction outside [0, 1]";
  return {};
}

// Every record is well formed and each level is sorted by vertex key. Reports the first bad light of a
// level only: a broken build would otherwise bury the log under millions of identical failures.
void expectWellFormed(const Hierarchy& h) {
  ASSERT_EQ(h.levels.size(), size_t(h.grid.levels) + 1);
  EXPECT_TRUE(h.levels[0].empty());
  for (int level = 1; level <= h.grid.levels; ++level) {
    const std::vector<GridLight>& lights = h.levels[level];
    for (size_t i = 0; i < lights.size(); ++i) {
      std::string problem = problemWith(lights[i], h.grid, level);
      if (problem.empty() && i > 0 && !(packVertex(lights[i - 1].vertex) < packVertex(lights[i].vertex)))
        problem = "not sorted by vertex key";
      if (!problem.empty()) {
        ADD_FAILURE() << "level " << level << ", light " << i << ": " << problem;
        break;
      }
    }
  }
}

void checkBuilds(const std::vector<Light>& lights, int levels) {
  const GridGeometry grid = makeGrid(lights, levels, kEMin);
  for (const auto& [name, build] : kBuilds) {
    SCOPED_TRACE(std::string(name) + " build, L = " + std::to_string(levels));
    const Hierarchy h = build(lights, grid);
    expectWellFormed(h);
    expectMomentsConserved(h, lights);
  }
}

TEST(Build, RandomSetsConserveEnergyAndMoments) {
  for (size_t count : {1000, 100000}) {
    for (bool oriented : {false, true}) {
      SCOPED_TRACE(std::to_string(count) + (oriented ? " oriented" : " omni") + " lights");
      const std::vector<Light> lights = test::randomCube(count, 100 + count + oriented, oriented);
      checkBuilds(lights, chooseLevelCount(lights, kEMin));
    }
  }
}

TEST(Build, ExtremeSetsConserveEnergyAndMoments) {
  for (const auto& [name, lights] : test::extremeSets()) {
    for (int levels : {1, chooseLevelCount(lights, kEMin), kMaxLevels}) {
      SCOPED_TRACE(name);
      checkBuilds(lights, levels);
    }
  }
}

TEST(Build, MixedOmniAndOrientedLightsKeepTheirShares) {
  std::vector<Light> lights = test::randomCube(5000, 7, true);
  for (size_t i = 0; i < lights.size(); i += 3) lights[i].normal = glm::vec3(0.0f);
  checkBuilds(lights, chooseLevelCount(lights, kEMin));
}

// The paper's fast path starts from the same S1 as the reference.
TEST(Build, ScatterAndGatherAgreeExactlyOnS1) {
  const std::vector<Light> lights = test::randomCube(20000, 8, true);
  const GridGeometry grid = makeGrid(lights, chooseLevelCount(lights, kEMin), kEMin);
  const Hierarchy scatter = buildScatter(lights, grid), gather = buildGather(lights, grid);
  ASSERT_EQ(scatter.levels[1].size(), gather.levels[1].size());
  for (size_t i = 0; i < scatter.levels[1].size(); ++i) {
    const GridLight &a = scatter.levels[1][i], &b = gather.levels[1][i];
    EXPECT_EQ(a.vertex, b.vertex);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.intensity, b.intensity);
    EXPECT_EQ(a.variance, b.variance);
    EXPECT_EQ(a.meanNormal, b.meanNormal);
    EXPECT_EQ(a.omniFraction, b.omniFraction);
    if (HasFailure()) return;  // one mismatch says it all
  }
}

// Above S1 the gather splats twice, which widens each light's footprint by at most one vertex:
// every vertex the gather fills is next to one the scatter fills, and the gather loses none.
TEST(Build, GatherOnlySmoothsCoarserLevels) {
  const std::vector<Light> lights = test::randomCube(20000, 9, false);
  const GridGeometry grid = makeGrid(lights, chooseLevelCount(lights, kEMin), kEMin);
  const Hierarchy scatter = buildScatter(lights, grid), gather = buildGather(lights, grid);
  for (int level = 2; level <= grid.levels; ++level) {
    std::unordered_map<uint64_t, const GridLight*> scattered;
    for (const GridLight& light : scatter.levels[level]) scattered[packVertex(light.vertex)] = &light;
    EXPECT_GE(gather.levels[level].size(), scatter.levels[level].size());
    for (const GridLight& light : gather.levels[level]) {
      bool nearScattered = false;
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const glm::ivec3 v = light.vertex + glm::ivec3(dx, dy, dz);
            if (glm::all(glm::greaterThanEqual(v, glm::ivec3(0))) && scattered.count(packVertex(v)))
              nearScattered = true;
          }
      ASSERT_TRUE(nearScattered) << "level " << level;
    }
  }
}

// Accumulating offsets from the vertex keeps the variance as accurate 1e5 from the origin as at it.
// Accumulating absolute positions would cancel p² ~ 1e10 against h² ~ 1 and lose ~1e-6 absolute.
TEST(Build, FarFromTheOriginMatchesTheSameLightsAtTheOrigin) {
  const glm::dvec3 offset(1e5, -1e5, 1e5);
  const std::vector<Light> far = test::randomCube(5000, 10, true, offset, 10.0);
  std::vector<Light> near = far;
  for (Light& light : near) light.position = glm::vec3(glm::dvec3(light.position) - offset);  // exact in float

  const int levels = chooseLevelCount(far, kEMin);
  ASSERT_EQ(levels, chooseLevelCount(near, kEMin));
  const GridGeometry farGrid = makeGrid(far, levels, kEMin), nearGrid = makeGrid(near, levels, kEMin);
  for (const auto& [name, build] : kBuilds) {
    SCOPED_TRACE(name);
    const Hierarchy a = build(far, farGrid), b = build(near, nearGrid);
    for (int level = 1; level <= levels; ++level) {
      const double h = farGrid.cellSize(level);
      ASSERT_EQ(a.levels[level].size(), b.levels[level].size());
      for (size_t i = 0; i < a.levels[level].size(); ++i) {
        const GridLight &p = a.levels[level][i], &q = b.levels[level][i];
        EXPECT_EQ(p.vertex, q.vertex);
        for (int axis = 0; axis < 3; ++axis) {
          EXPECT_NEAR(p.position[axis] - offset[axis], q.position[axis], 1e-9 * h);
          EXPECT_NEAR(p.variance[axis], q.variance[axis], 1e-9 * h * h);
          EXPECT_NEAR(p.intensity[axis], q.intensity[axis], 1e-9 * q.intensity[axis]);
        }
        if (HasFailure()) return;
      }
    }
  }
}

TEST(Build, OneLightIsItselfOnEveryLevel) {
  const Light light{glm::vec3(0.3f, -2.0f, 7.0f), glm::vec3(1.0f, 2.0f, 3.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
  for (int levels : {1, 4, kMaxLevels}) {
    const GridGeometry grid = makeGrid({light}, levels, kEMin);
    const double H = grid.topCellSize;
    for (const auto& [name, build] : kBuilds) {
      const Hierarchy h = build({light}, grid);
      for (int level = 1; level <= levels; ++level) {
        SCOPED_TRACE(std::string(name) + ", level " + std::to_string(level));
        // The light sits at the grid centre: on a vertex below the top level, at the centre
        // of the single top cell. Each vertex that sees it reproduces it exactly.
        ASSERT_FALSE(h.levels[level].empty());
        for (const GridLight& g : h.levels[level]) {
          EXPECT_NEAR(glm::distance(g.position, glm::dvec3(light.position)), 0.0, 1e-12 * H);
          EXPECT_NEAR(glm::length(g.variance), 0.0, 1e-12 * H * H);
          EXPECT_NEAR(glm::distance(g.meanNormal, glm::dvec3(light.normal)), 0.0, 1e-12);
          EXPECT_EQ(g.omniFraction, 0.0);
        }
        EXPECT_NEAR(glm::distance(test::totalIntensity(h.levels[level]), glm::dvec3(light.intensity)), 0.0, 1e-12);
      }
    }
  }
}

TEST(Build, CoincidentLightsCollapseToTheirPoint) {
  std::vector<Light> lights = test::randomCube(10000, 16, true);
  const glm::vec3 point(0.1f, 0.2f, 0.3f);
  for (Light& light : lights) light.position = point;
  const GridGeometry grid = makeGrid(lights, kMaxLevels, kEMin);
  for (const auto& [name, build] : kBuilds) {
    const Hierarchy h = build(lights, grid);
    for (int level = 1; level <= grid.levels; ++level) {
      SCOPED_TRACE(std::string(name) + ", level " + std::to_string(level));
      EXPECT_LE(h.levels[level].size(), 8u);
      for (const GridLight& g : h.levels[level]) {
        EXPECT_NEAR(glm::distance(g.position, glm::dvec3(point)), 0.0, 1e-12 * grid.topCellSize);
        EXPECT_NEAR(glm::length(g.variance), 0.0, 1e-12 * grid.topCellSize * grid.topCellSize);
        EXPECT_LT(glm::length(g.meanNormal), 0.1);  // 10K random normals nearly cancel
        if (HasFailure()) return;
      }
    }
  }
}

TEST(Build, PlanarLightsStayInTheirPlane) {
  std::vector<Light> lights = test::randomCube(10000, 17, false);
  for (Light& light : lights) light.position.y = -0.625f;
  const GridGeometry grid = makeGrid(lights, chooseLevelCount(lights, kEMin), kEMin);
  for (const auto& [name, build] : kBuilds) {
    const Hierarchy h = build(lights, grid);
    for (int level = 1; level <= grid.levels; ++level)
      for (const GridLight& g : h.levels[level]) {
        EXPECT_NEAR(g.position.y, -0.625, 1e-12) << name;
        EXPECT_NEAR(g.variance.y, 0.0, 1e-12 * grid.topCellSize * grid.topCellSize) << name;
        if (HasFailure()) return;
      }
  }
}

TEST(Build, NoLitLightsGiveAnEmptyHierarchy) {
  for (const auto& lights : {std::vector<Light>{}, std::vector<Light>(50, Light{glm::vec3(1.0f), glm::vec3(0.0f)})}) {
    for (const auto& [name, build] : kBuilds) {
      const Hierarchy h = build(lights, makeGrid(lights, 5, kEMin));
      EXPECT_EQ(h.levels.size(), 6u) << name;
      EXPECT_EQ(h.lightCount(), 0u) << name;
    }
  }
}

// Memory follows occupied vertices: 21 levels over 10 lights is at most 8 vertices per light per level,
// where a dense level 1 would have (2^20 + 1)^3 vertices.
TEST(Build, DeepHierarchiesStaySmallAndFast) {
  const std::vector<Light> lights = test::randomCube(10, 18, true);
  const GridGeometry grid = makeGrid(lights, kMaxLevels, kEMin);
  const auto start = std::chrono::steady_clock::now();
  for (const auto& [name, build] : kBuilds) {
    const Hierarchy h = build(lights, grid);
    EXPECT_LE(h.lightCount(), 8u * 10u * kMaxLevels) << name;
    EXPECT_EQ(h.levels[kMaxLevels].size(), 8u) << name;  // the top cell's 8 corners
    expectMomentsConserved(h, lights);
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

TEST(Build, RejectsInvalidInput) {
  std::vector<Light> lights = test::randomCube(10, 19, false);
  const GridGeometry grid = makeGrid(lights, 3, kEMin);
  lights[4].intensity.g = -1.0f;
  for (const auto& [name, build] : kBuilds) EXPECT_THROW(build(lights, grid), std::invalid_argument) << name;
  GridGeometry tooDeep = grid;
  tooDeep.levels = kMaxLevels + 1;
  lights[4].intensity.g = 1.0f;
  for (const auto& [name, build] : kBuilds) EXPECT_THROW(build(lights, tooDeep), std::invalid_argument) << name;
}

}  // namespace
}  // namespace lgh
