// VPL generation: the flux the VPLs carry is exact in expectation. In a closed box of uniform albedo
// every path hits, so the first bounce carries rho x emitted power to float precision; in the Cornell
// box the first bounce's flux is compared with an independent CPU Monte Carlo estimate of emitted
// power x mean albedo at the first hit.
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <random>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "lgh/light.h"
#include "render/passes/vpl_pass.h"
#include "shared/lgh_types.h"
#include "shared/ray_triangle.h"

namespace lgh::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 totalFlux(const gl::Buffer& lights, size_t count) {
  glm::dvec3 sum(0.0);
  for (const gpu::GpuLight& l : lights.download<gpu::GpuLight>(count)) sum += kPi * glm::dvec3(l.intensity);
  return sum;
}

// A closed 2 m box (inward faces) of albedo 0.5 with a light inside.
std::filesystem::path writeClosedBox(const TempDir& dir, const LightDesc& light, const glm::quat& rotation) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 1}));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({box({0, 0, 0}, {1, 1, 1}, grey)})));
  w.addNode(NodeDesc{}.withLight(w.addLight(light)).translated({0.2f, 0.3f, -0.1f}).rotated(rotation));
  return w.write(dir / "box.gltf");
}

class VplTest : public GLTest {
 protected:
  TempDir dir;
};

TEST_F(VplTest, ClosedBoxFirstBounceCarriesAlbedoTimesPower) {
  for (const char* type : {"point", "spot"}) {
    SCOPED_TRACE(type);
    const glm::quat down = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));
    const Scene scene =
        loadScene(writeClosedBox(dir, LightDesc{}.ofType(type).withIntensity(5.0).withCone(0.2, 0.9), down));
    const SceneGpu gpu(scene);
    VplPass pass(gpu);
    const size_t budget = 100000;
    gl::Buffer out({"test", "out"}, VplPass::maxVplCount(budget, 1) * sizeof(gpu::GpuLight));
    const size_t count = pass.tracePaths(out, 0, budget, 1, 7);
    EXPECT_EQ(count, budget) << "every path in a closed box must hit";
    const glm::dvec3 flux = totalFlux(out, count);
    const glm::dvec3 expected = 0.5 * pass.emitters().totalPower;
    // A point light's paths all carry the same flux: exact to float rounding. A spot light's carry
    // its falloff as a weight, so the sum is a Monte Carlo estimate: allow a 4-sigma band.
    const double tolerance = std::string(type) == "point" ? 1e-4 : 0.02;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(flux[k], expected[k], tolerance * expected[k]);
  }
}

TEST_F(VplTest, EveryBounceKeepsAlbedoTimesThePreviousFlux) {
  const Scene scene = loadScene(writeClosedBox(dir, LightDesc{}.withIntensity(2.0), glm::quat(1, 0, 0, 0)));
  const SceneGpu gpu(scene);
  VplPass pass(gpu);
  const size_t budget = 3 * 30000;
  gl::Buffer out({"test", "out"}, VplPass::maxVplCount(budget, 3) * sizeof(gpu::GpuLight));
  const size_t count = pass.tracePaths(out, 0, budget, 3, 11);
  EXPECT_EQ(count, budget);
  // Bounces 1, 2, 3 reflect 0.5, 0.25 and 0.125 of the emitted power.
  const glm::dvec3 expected = (0.5 + 0.25 + 0.125) * pass.emitters().totalPower;
  const glm::dvec3 flux = totalFlux(out, count);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(flux[k], expected[k], 1e-4 * expected[k]);
}

// S0 comes out in the same order on every run (paths and samples write fixed slots, compacted in slot
// order), so frames drawing S0 itself are reproducible: two runs with one seed give identical bytes,
// with VPLs at an offset after emitter samples as the renderer lays them out; path p's bounces are
// consecutive, so a 3-bounce path's VPLs carry halving flux in order.
TEST_F(VplTest, OrderDependsOnlyOnTheSeed) {
  const Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
  const SceneGpu gpu(scene);
  VplPass pass(gpu);
  const size_t budget = 3 * 20000, offset = 100;
  auto trace = [&](std::uint32_t seed) {
    gl::Buffer out({"test", "out"}, (offset + VplPass::maxVplCount(budget, 3)) * sizeof(gpu::GpuLight));
    out.clear();
    const size_t count = pass.tracePaths(out, offset, budget, 3, seed);
    return out.download<gpu::GpuLight>(count, offset);
  };
  const std::vector<gpu::GpuLight> a = trace(5), b = trace(5), c = trace(6);
  ASSERT_GT(a.size(), budget / 2);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::GpuLight)), 0) << "same seed, other order";
  EXPECT_TRUE(c.size() != a.size() || std::memcmp(a.data(), c.data(), a.size() * sizeof(gpu::GpuLight)) != 0);
  for (const gpu::GpuLight& l : a) ASSERT_NE(l.flags, 0u) << "an empty slot survived the compaction";
}

// Paths and emitter samples are generated in batches whose records fit one storage block (S0 itself may not:
// it is written by ranges). Batches of 997 paths, at an unaligned offset, give S0 byte for byte as one batch.
TEST_F(VplTest, BatchesGiveTheSameLightsAsOneBatch) {
  const Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
  const SceneGpu gpu(scene);
  VplPass pass(gpu);
  const size_t budget = 3 * 20000, offset = 37;
  auto trace = [&](size_t batchLimit) {
    pass.setBatchLimit(batchLimit);
    gl::Buffer out({"test", "out"}, (offset + VplPass::maxVplCount(budget, 3)) * sizeof(gpu::GpuLight));
    out.clear();
    const size_t count = pass.tracePaths(out, offset, budget, 3, 5);
    return out.download<gpu::GpuLight>(count, offset);
  };
  const std::vector<gpu::GpuLight> one = trace(0), batched = trace(997);
  ASSERT_GT(one.size(), budget / 2);
  ASSERT_EQ(one.size(), batched.size());
  EXPECT_EQ(std::memcmp(one.data(), batched.data(), one.size() * sizeof(gpu::GpuLight)), 0);
}

// Cornell box: the spot light's first-bounce flux against a CPU estimate of power x mean hit albedo,
// sampled independently (same emission distribution, brute-force intersection in double).
TEST_F(VplTest, CornellFirstBounceMatchesPowerTimesMeanHitAlbedo) {
  const Scene scene = loadScene(sourceDir() / "data/cornell_box.gltf");
  ASSERT_EQ(scene.lights.size(), 1u);
  const PunctualLight& spot = scene.lights[0];
  const SceneGpu gpu(scene);
  VplPass pass(gpu);
  const size_t budget = 200000;
  gl::Buffer out({"test", "out"}, VplPass::maxVplCount(budget, 1) * sizeof(gpu::GpuLight));
  const size_t count = pass.tracePaths(out, 0, budget, 1, 3);
  const double gpuFlux = luminance(totalFlux(out, count));

  // CPU: directions uniform in the outer cone weighted by the falloff, as the spot's emission is.
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int samples = 40000;
  double sum = 0, sumSq = 0;
  const double coneSolidAngle = 2 * kPi * (1 - spot.outerConeCos);
  for (int i = 0; i < samples; ++i) {
    const double c = 1 - u(rng) * (1 - spot.outerConeCos), s = std::sqrt(std::max(0.0, 1 - c * c)),
                 phi = 2 * kPi * u(rng);
    glm::dvec3 t = glm::abs(spot.direction.x) < 0.9f ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t = glm::normalize(glm::cross(t, glm::dvec3(spot.direction)));
    const glm::dvec3 b = glm::cross(glm::dvec3(spot.direction), t);
    const glm::dvec3 d = s * std::cos(phi) * t + s * std::sin(phi) * b + c * glm::dvec3(spot.direction);
    const double ramp =
        std::clamp((c - spot.outerConeCos) / std::max(double(spot.innerConeCos - spot.outerConeCos), 1e-4), 0.0, 1.0);
    double bestT = 1e30, albedo = 0;
    for (size_t tri = 0; tri < scene.triangleCount(); ++tri) {
      const glm::vec3 v0 = scene.positions[scene.indices[3 * tri]];
      glm::vec3 hit;
      if (gpu::intersectTriangle(spot.position, glm::vec3(d), v0, scene.positions[scene.indices[3 * tri + 1]] - v0,
                                 scene.positions[scene.indices[3 * tri + 2]] - v0, 0.0f, float(bestT), hit)) {
        bestT = hit.x;
        albedo = luminance(glm::dvec3(scene.materials[scene.triangleMaterials[tri]].baseColorFactor));
      }
    }
    const double flux = luminance(glm::dvec3(spot.intensity)) * ramp * ramp * coneSolidAngle * albedo;
    sum += flux;
    sumSq += flux * flux;
  }
  const double mean = sum / samples, sigma = std::sqrt((sumSq / samples - mean * mean) / samples);
  // The GPU estimate has its own (smaller, 5x more samples) error: a 5-sigma band on the combined error.
  EXPECT_NEAR(gpuFlux, mean, 5 * sigma * std::sqrt(1.0 + double(samples) / double(budget)))
      << "GPU " << gpuFlux << " vs CPU " << mean << " +- " << sigma;
}

TEST_F(VplTest, EmissiveTriangleSamplesCarryTheEmittedPower) {
  LGH_REQUIRE_SHARED_SCENE(path, "cornell_emissive/cornell_emissive.gltf");
  const Scene scene = loadScene(path);
  const SceneGpu gpu(scene);
  VplPass pass(gpu);
  const size_t samples = 100000;
  gl::Buffer out({"test", "out"}, samples * sizeof(gpu::GpuLight));
  ASSERT_EQ(pass.sampleEmissiveTriangles(out, 0, samples, 5), samples);
  const glm::dvec3 flux = totalFlux(out, samples), expected = pass.emissiveTriangles().totalPower;
  // Luminance is exact (selection is proportional to it); each channel is a Monte Carlo estimate.
  EXPECT_NEAR(luminance(flux), luminance(expected), 1e-4 * luminance(expected));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(flux[k], expected[k], 0.03 * luminance(expected));
  // Emissive triangles' paths: first-bounce VPLs carry at most the emitted power times the largest albedo.
  gl::Buffer vpls({"test", "vpls"}, VplPass::maxVplCount(50000, 1) * sizeof(gpu::GpuLight));
  const size_t n = pass.tracePaths(vpls, 0, 50000, 1, 9);
  EXPECT_GT(n, 40000u);
  EXPECT_LT(luminance(totalFlux(vpls, n)), luminance(pass.emitters().totalPower));
}

}  // namespace
}  // namespace lgh::test
