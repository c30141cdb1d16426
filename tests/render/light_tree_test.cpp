// The GPU light tree (LightTreePass) against the CPU reference (lgh::buildLightTree), node for node:
// boxes and light indices bit for bit, intensities to float rounding (the GPU's luminance is a dot product,
// whose summation order is the driver's); on random lights with some unlit, on 1 light, on 256 coincident
// lights and at 2^k and 2^k + 1 lights; and the same tree on every run.
#include "lgh/light_tree.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gl_test_env.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_tree_pass.h"

namespace lgh::test {
namespace {

class LightTreeGpuTest : public GLTest {};

// count lights in a box of varied extent per axis, grey or coloured, a few unlit, oriented or omni.
std::vector<Light> randomLights(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Light> lights(count);
  for (Light& l : lights) {
    l.position = glm::vec3(4.0f * unit(rng) - 2.0f, 0.5f * unit(rng), 10.0f * unit(rng));
    l.intensity = unit(rng) < 0.05f ? glm::vec3(0.0f) : glm::vec3(unit(rng), unit(rng), unit(rng)) * 3.0f;
    if (unit(rng) < 0.5f) l.normal = glm::normalize(glm::vec3(unit(rng) - 0.5f, unit(rng) + 0.1f, unit(rng) - 0.5f));
  }
  return lights;
}

void expectTreesEqual(const std::vector<Light>& lights) {
  // The CPU reference sees the lights as the GPU holds them.
  const std::vector<gpu::GpuLight> gpuLights = toGpuLights(lights);
  const LightTree cpu = buildLightTree(fromGpuLights(gpuLights));
  const gl::Buffer buffer = gl::Buffer::fromVector({"test", "data"}, gpuLights);
  LightTreePass pass;
  GpuLightTree gpu;
  pass.execute(buffer, lights.size(), gpu);
  ASSERT_EQ(gpu.levels, cpu.levels);
  ASSERT_EQ(gpu.leafCount, cpu.leafCount);
  const std::vector<gpu::GpuLightTreeNode> nodes = gpu.download();
  ASSERT_EQ(nodes.size(), cpu.nodes.size());
  for (size_t i = 1; i < nodes.size(); ++i) {
    SCOPED_TRACE("node " + std::to_string(i));
    const LightTreeNode& want = cpu.nodes[i];
    ASSERT_EQ(nodes[i].lightIndex, want.lightIndex);
    ASSERT_EQ(nodes[i].boundMin, want.boundMin);
    ASSERT_EQ(nodes[i].boundMax, want.boundMax);
    ASSERT_NEAR(nodes[i].intensity, want.intensity, 1e-6f * want.intensity);
  }
  // Deterministic: a second build is the same bit for bit.
  pass.execute(buffer, lights.size(), gpu);
  const std::vector<gpu::GpuLightTreeNode> again = gpu.download();
  for (size_t i = 1; i < nodes.size(); ++i) {
    ASSERT_EQ(again[i].lightIndex, nodes[i].lightIndex) << "node " << i;
    ASSERT_EQ(again[i].intensity, nodes[i].intensity) << "node " << i;
  }
}

TEST_F(LightTreeGpuTest, EqualsTheCpuReferenceOnRandomLights) { expectTreesEqual(randomLights(5000, 7)); }

TEST_F(LightTreeGpuTest, EqualsTheCpuReferenceOnOneLight) { expectTreesEqual(randomLights(1, 3)); }

TEST_F(LightTreeGpuTest, EqualsTheCpuReferenceOnCoincidentLights) {
  std::vector<Light> lights = randomLights(256, 11);
  for (Light& l : lights) l.position = glm::vec3(0.25f, -1.0f, 3.0f);
  expectTreesEqual(lights);
}

TEST_F(LightTreeGpuTest, EqualsTheCpuReferenceAtPowersOfTwoAndOneMore) {
  for (size_t count : {size_t(2), size_t(3), size_t(1024), size_t(1025), size_t(65536), size_t(65537)}) {
    SCOPED_TRACE(std::to_string(count) + " lights");
    expectTreesEqual(randomLights(count, uint32_t(count)));
  }
}

TEST_F(LightTreeGpuTest, NoLightsNoTree) {
  LightTreePass pass;
  GpuLightTree tree;
  pass.execute(gl::Buffer({"test", "no lights"}, sizeof(gpu::GpuLight)), 0, tree);
  EXPECT_EQ(tree.leafCount, 0u);
  EXPECT_EQ(tree.levels, 0);
}

}  // namespace
}  // namespace lgh::test
