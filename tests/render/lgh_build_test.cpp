// The GPU hierarchy build against the CPU library (lgh/, double precision) on the same lights:
// the same grid lights per level, centres within 1e-4 h, intensities within 1e-4 relative, energy
// kept per level, determinism, chunking, the automatic level count, and the extremes of docs/design.md §8.
#include <algorithm>
#include <cstring>
#include <map>
#include <random>

#include "gl_test_env.h"
#include "lgh/hierarchy.h"
#include "render/passes/lgh_build_pass.h"
#include "render/scene/scene.h"
#include "render/scene/surface_samples.h"

namespace lgh::test {
namespace {

std::vector<Light> randomLights(size_t n, std::uint32_t seed, bool oriented, glm::vec3 offset = glm::vec3(0.0f),
                                float extent = 10.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), intensity(0.5f, 2.0f);
  std::normal_distribution<float> g;
  std::vector<Light> lights(n);
  for (Light& l : lights) {
    l.position = offset + extent * glm::vec3(u(rng), u(rng), u(rng));
    l.intensity = glm::vec3(intensity(rng), intensity(rng), intensity(rng));
    if (oriented) l.normal = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
  }
  return lights;
}

struct GpuBuild {
  GpuHierarchy hierarchy;
  std::vector<Light> seen;  // what the GPU saw (octahedral normals decoded)
};

GpuBuild buildOnGpu(const std::vector<Light>& lights, LghBuildOptions options = {}) {
  static LghBuildPass pass(glContext().hasExtension("GL_NV_shader_atomic_float"));
  const std::vector<gpu::GpuLight> gpuLights = toGpuLights(lights);
  const gl::Buffer buffer = gl::Buffer::fromVector({"test", "data"}, gpuLights);
  GpuBuild build;
  if (options.eMin <= 0) options.eMin = 1e-4;
  pass.execute(buffer, lights.size(), options, build.hierarchy);
  build.seen = fromGpuLights(gpuLights);
  return build;
}

glm::ivec3 vertexOf(std::uint32_t key, const GridGeometry& grid, int level) {
  const std::uint32_t n = std::uint32_t(grid.cellsPerAxis(level)) + 1;
  return glm::ivec3(int(key % n), int((key / n) % n), int(key / (n * n)));
}

glm::dvec3 levelEnergy(const std::vector<gpu::GpuGridLight>& level) {
  glm::dvec3 sum(0.0);
  for (const auto& g : level) sum += glm::dvec3(g.intensity);
  return sum;
}

// GPU grid lights vs the CPU build, level by level. Keys present on one side only must carry
// negligible light: they come from a light within float rounding of a cell boundary, where the CPU
// (double) and the GPU (float) can disagree about a trilinear weight of ~1e-7.
void expectMatchesCpu(const GpuHierarchy& gpu, const Hierarchy& cpu, const char* label) {
  ASSERT_EQ(cpu.levels.size(), gpu.levels.size()) << label;
  for (int level = 1; level < int(gpu.levels.size()); ++level) {
    SCOPED_TRACE(std::string(label) + ", level " + std::to_string(level));
    const std::vector<gpu::GpuGridLight> gpuLevel = gpu.downloadLevel(level);
    std::map<std::uint64_t, const GridLight*> cpuByKey;
    double levelLum = 0;
    for (const GridLight& g : cpu.levels[size_t(level)]) {
      cpuByKey[packVertex(g.vertex)] = &g;
      levelLum += luminance(g.intensity);
    }
    const double h = gpu.grid.cellSize(level);
    size_t matched = 0, unmatchedGpu = 0;
    for (const gpu::GpuGridLight& g : gpuLevel) {
      ASSERT_EQ(g.level, std::uint32_t(level));
      auto it = cpuByKey.find(packVertex(vertexOf(g.vertexKey, gpu.grid, level)));
      if (it == cpuByKey.end()) {
        ++unmatchedGpu;
        EXPECT_LT(luminance(glm::dvec3(g.intensity)), 1e-6 * levelLum) << "GPU-only grid light carries light";
        continue;
      }
      const GridLight& c = *it->second;
      ++matched;
      const double lum = luminance(c.intensity);
      if (lum < 1e-6 * levelLum) continue;  // a boundary sliver: its centre is ill-conditioned
      EXPECT_LE(glm::length(glm::dvec3(g.position) - c.position), 1e-4 * h);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(g.intensity[k], c.intensity[k], 1e-4 * c.intensity[k] + 1e-12);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(g.variance[k], c.variance[k], 1e-4 * h * h);
      EXPECT_LE(glm::length(glm::dvec3(g.meanNormal) - c.meanNormal), 1e-4);
      EXPECT_NEAR(g.omniFraction, c.omniFraction, 1e-4);
      if (::testing::Test::HasFailure()) return;
    }
    size_t significantCpuOnly = 0;
    for (const GridLight& c : cpu.levels[size_t(level)])
      if (luminance(c.intensity) >= 1e-6 * levelLum) ++significantCpuOnly;
    EXPECT_GE(matched, significantCpuOnly) << "CPU grid lights missing on the GPU";
    EXPECT_LE(unmatchedGpu, gpuLevel.size() / 1000 + 8);
  }
}

class LghBuildTest : public GLTest {};

TEST_F(LghBuildTest, MatchesCpuGatherBuildOnRandomLights) {
  for (size_t n : {size_t(1000), size_t(100000), size_t(1000000)}) {
    SCOPED_TRACE(std::to_string(n) + " lights");
    const GpuBuild gpu = buildOnGpu(randomLights(n, std::uint32_t(n), /*oriented=*/n != 1000));
    const Hierarchy cpu = buildGather(gpu.seen, gpu.hierarchy.grid);
    expectMatchesCpu(gpu.hierarchy, cpu, "random");
    std::printf("[ LGH      ] %zu lights: L=%d, %zu grid lights\n", n, gpu.hierarchy.grid.levels,
                gpu.hierarchy.gridLightCount);
  }
}

TEST_F(LghBuildTest, MatchesCpuOnSponzaSurfaceLights) {
  LGH_REQUIRE_SHARED_SCENE(path, "sponza_sun/sponza_sun.gltf");
  const Scene scene = loadScene(path);
  const GpuBuild gpu = buildOnGpu(sampleSurfaceLights(scene, 200000, 5, 1000.0f));
  expectMatchesCpu(gpu.hierarchy, buildGather(gpu.seen, gpu.hierarchy.grid), "sponza");
}

TEST_F(LghBuildTest, ScatterEveryLevelMatchesCpuScatterBuild) {
  LghBuildOptions options;
  options.gatherCoarseLevels = false;
  const GpuBuild gpu = buildOnGpu(randomLights(20000, 3, true), options);
  expectMatchesCpu(gpu.hierarchy, buildScatter(gpu.seen, gpu.hierarchy.grid), "scatter");
}

TEST_F(LghBuildTest, AutomaticLevelCountMatchesCpu) {
  for (size_t n : {size_t(1), size_t(100), size_t(10000), size_t(200000)}) {
    const GpuBuild gpu = buildOnGpu(randomLights(n, 9, false));
    EXPECT_EQ(gpu.hierarchy.grid.levels, std::min(chooseLevelCount(gpu.seen, 1e-4), LghBuildPass::kMaxLevels))
        << n << " lights";
  }
}

TEST_F(LghBuildTest, EnergyIsKeptOnEveryLevelEvenWhenAllLightsCoincide) {
  // 200,000 lights on one point share 8 vertices: float atomics would stop adding long before the
  // end (2^24 ratio); fixed point keeps every one.
  std::vector<Light> lights(200000, Light{{1.5f, -2.0f, 3.25f}, {0.3f, 0.2f, 0.1f}, {0, 1, 0}});
  const GpuBuild gpu = buildOnGpu(lights);
  glm::dvec3 s0(0.0);
  for (const Light& l : gpu.seen) s0 += glm::dvec3(l.intensity);
  for (int level = 1; level <= gpu.hierarchy.grid.levels; ++level) {
    const glm::dvec3 e = levelEnergy(gpu.hierarchy.downloadLevel(level));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], s0[k], 1e-5 * s0[k]) << "level " << level;
  }
}

TEST_F(LghBuildTest, DeterministicUnderShufflingAndChunking) {
  std::vector<Light> lights = randomLights(50000, 21, true);
  const GpuBuild a = buildOnGpu(lights);
  std::shuffle(lights.begin(), lights.end(), std::mt19937(4));
  LghBuildOptions chunked;
  chunked.maxLightsPerDispatch = 1024;  // 49 dispatches per step
  const GpuBuild b = buildOnGpu(lights, chunked);
  ASSERT_EQ(a.hierarchy.gridLightCount, b.hierarchy.gridLightCount);
  const auto ga = a.hierarchy.gridLights.downloadAll<gpu::GpuGridLight>();
  const auto gb = b.hierarchy.gridLights.downloadAll<gpu::GpuGridLight>();
  ASSERT_EQ(ga.size(), gb.size());
  EXPECT_EQ(0, std::memcmp(ga.data(), gb.data(), ga.size() * sizeof(gpu::GpuGridLight)))
      << "shuffled input or chunked dispatch changed the hierarchy";
}

TEST_F(LghBuildTest, FloatAtomicsKeepEnergyOnSpreadLights) {
  if (!glContext().hasExtension("GL_NV_shader_atomic_float")) GTEST_SKIP() << "no GL_NV_shader_atomic_float";
  LghBuildOptions options;
  options.floatAtomics = true;
  const GpuBuild gpu = buildOnGpu(randomLights(100000, 8, true), options);
  expectMatchesCpu(gpu.hierarchy, buildGather(gpu.seen, gpu.hierarchy.grid), "float atomics");
}

struct Extreme {
  const char* name;
  std::vector<Light> lights;
  int levels;
};

TEST_F(LghBuildTest, ExtremesStayFiniteAndKeepEnergy) {
  std::vector<Extreme> cases;
  cases.push_back({"one light", {Light{{1, 2, 3}, {1, 1, 1}, {}}}, 0});
  cases.push_back({"one light, 11 levels", {Light{{1, 2, 3}, {1, 1, 1}, {}}}, 11});
  std::vector<Light> plane = randomLights(20000, 2, true);
  for (Light& l : plane) l.position.y = 0.5f;
  cases.push_back({"planar", plane, 0});
  std::vector<Light> wide = randomLights(20000, 3, false);
  for (size_t i = 0; i < wide.size(); ++i) wide[i].intensity *= (i % 2 ? 1e8f : 1e-8f);
  cases.push_back({"1e-8 and 1e8", wide, 0});
  cases.push_back({"offset 1e5", randomLights(20000, 4, true, glm::vec3(1e5f)), 0});
  cases.push_back({"one level", randomLights(5000, 5, false), 1});
  cases.push_back({"max levels", randomLights(5000, 6, false), LghBuildPass::kMaxLevels});
  std::vector<Light> dark = randomLights(100, 7, false);
  for (Light& l : dark) l.intensity = glm::vec3(0);
  cases.push_back({"all dark", dark, 0});
  for (const Extreme& c : cases) {
    SCOPED_TRACE(c.name);
    LghBuildOptions options;
    options.levels = c.levels;
    const GpuBuild gpu = buildOnGpu(c.lights, options);
    glm::dvec3 s0(0.0);
    for (const Light& l : gpu.seen) s0 += glm::dvec3(l.intensity);
    for (int level = 1; level <= gpu.hierarchy.grid.levels; ++level) {
      const auto lights = gpu.hierarchy.downloadLevel(level);
      for (const auto& g : lights) {
        for (const glm::vec3& v : {g.position, g.intensity, g.variance, g.meanNormal})
          ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << "level " << level;
        ASSERT_TRUE(std::isfinite(g.omniFraction));
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(g.variance, glm::vec3(0))));
      }
      const glm::dvec3 e = levelEnergy(lights);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], s0[k], 1e-5 * s0[k] + 1e-30) << "level " << level;
    }
  }
}

TEST_F(LghBuildTest, NoLightsGiveAnEmptyHierarchy) {
  const GpuBuild gpu = buildOnGpu({});
  EXPECT_EQ(gpu.hierarchy.gridLightCount, 0u);
}

}  // namespace
}  // namespace lgh::test
