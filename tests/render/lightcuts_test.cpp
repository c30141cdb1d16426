// The stochastic lightcuts on the GPU (glsl/shared/light_tree.glsl, glsl/rtslc.comp) against the math:
// the leaf a descent reaches follows the CPU reference's product of child probabilities (chi-square), and
// the descent reports that product; the shadowed irradiance is unbiased (the mean of many single frames
// equals the exact shadowed sum within its standard error) and its accumulated error falls as
// frames^-1/2; every pixel's cut is a partition of the lit lights.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "../lgh/chi_square.h"
#include "exact_irradiance.h"
#include "gl_test_env.h"
#include "lgh/light_tree.h"
#include "render/gl/program.h"
#include "render/image_compare.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_tree_pass.h"
#include "render/passes/rtslc_pass.h"
#include "render/renderer.h"
#include "shared/bindings.h"

namespace lgh::test {
namespace {

class LightcutsTest : public GLTest {};

std::vector<Light> clusteredLights(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Light> lights(count);
  for (size_t i = 0; i < count; ++i) {
    // Three clusters of different brightness and extent, some lights behind the receiver's plane.
    const glm::vec3 centre = i % 3 == 0   ? glm::vec3(0, 2, 0)
                             : i % 3 == 1 ? glm::vec3(3, 0.5f, 1)
                                          : glm::vec3(-2, 1, -3);
    const float extent = i % 3 == 0 ? 0.5f : i % 3 == 1 ? 2.0f : 1.0f;
    lights[i].position = centre + extent * (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f);
    lights[i].intensity = glm::vec3(0.2f + unit(rng)) * (i % 3 == 0 ? 4.0f : 1.0f);
    if (i % 5 == 0) lights[i].intensity = glm::vec3(0.0f);
  }
  return lights;
}

// From the root and from an inner node, 400,000 descents at a shading point: the leaves reached follow
// the CPU reference's leaf probabilities, and each descent's probability is the reference's for its leaf;
// without a distance floor and with the shading's clamp distance as one (0.4: within it of many boxes).
TEST_F(LightcutsTest, DescentsFollowTheReferenceProbabilities) {
  const std::vector<gpu::GpuLight> gpuLights = toGpuLights(clusteredLights(300, 5));
  const LightTree cpu = buildLightTree(fromGpuLights(gpuLights));
  const gl::Buffer lights = gl::Buffer::fromVector({"test", "data"}, gpuLights);
  LightTreePass pass;
  GpuLightTree tree;
  pass.execute(lights, gpuLights.size(), tree);
  const glm::vec3 x(0.5f, -0.5f, 0.25f), n = glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f));
  gl::Program descent = gl::Program::compute("tests/light_tree_descent.comp");
  constexpr size_t kDescents = 400000;
  gl::Buffer leaves({"test", "leaves"}, kDescents * sizeof(GLuint)),
      probabilities({"test", "probabilities"}, kDescents * sizeof(float));
  for (auto [start, clampDistance] : {std::pair{1u, 0.0f}, {5u, 0.0f}, {1u, 0.4f}, {5u, 0.4f}}) {
    SCOPED_TRACE("from node " + std::to_string(start) + ", clamp distance " + std::to_string(clampDistance));
    const std::vector<double> expected =
        leafProbabilities(cpu, start, glm::dvec3(x), glm::dvec3(n), double(clampDistance));
    uint32_t depth = 0;
    while ((size_t(1) << depth) < expected.size()) ++depth;
    const uint32_t firstLeaf = start << depth;
    tree.nodes.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
    leaves.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
    probabilities.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
    descent.set("count", GLuint(kDescents));
    descent.set("startNode", GLuint(start));
    descent.set("leafCount", GLuint(tree.leafCount));
    descent.set("seed", GLuint(17 + start));
    descent.set("x", x);
    descent.set("n", n);
    descent.set("clampDistance", clampDistance);
    descent.dispatch1D(kDescents, 64);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<GLuint> reached = leaves.download<GLuint>(kDescents);
    const std::vector<float> reported = probabilities.download<float>(kDescents);
    std::vector<double> counts(expected.size(), 0.0);
    double dead = 0;
    for (size_t i = 0; i < kDescents; ++i) {
      if (reached[i] == 0) {
        ++dead;
        continue;
      }
      ASSERT_GE(reached[i], firstLeaf);
      const size_t leaf = reached[i] - firstLeaf;
      ASSERT_LT(leaf, expected.size());
      counts[leaf] += 1;
      // Each level's probability is rounded to the uniforms' 2^-24 steps (light_tree.glsl): within 1e-3 for
      // the levels' probabilities of the leaves drawn here (>= 1e-4 each).
      ASSERT_NEAR(reported[i], expected[leaf], 1e-3 * expected[leaf] + 1e-12) << "leaf " << reached[i];
    }
    double live = 0;
    for (double p : expected) live += p;
    // A dead branch is drawn as often as the probability mass the reference loses to them.
    EXPECT_NEAR(dead / kDescents, 1.0 - live, 5.0 * std::sqrt(std::max((1.0 - live) * live, 0.0) / kDescents) + 1e-9);
    std::vector<double> conditional = expected;
    for (double& p : conditional) p /= live;
    const ChiSquare test = chiSquare(counts, conditional);
    EXPECT_TRUE(test.passes()) << "chi-square " << test.statistic << " over " << test.dof
                               << " degrees of freedom (1% critical value " << test.critical01 << ")";
  }
}

class LightcutsFrameTest : public GLTest {
 protected:
  LightcutsFrameTest() : scene(loadScene(sourceDir() / "data" / "cornell_box.gltf")) {
    settings.image.width = 160;
    settings.image.height = 90;
    settings.inputLights.vpls = 2000;
    settings.inputLights.bounces = 1;
    settings.indirectMethod = IndirectMethod::Rtslc;
    settings.rtslc.samples = 4;
    settings.filter.passes = 0;  // raw
  }
  CameraView view() const {
    return makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  }
  Scene scene;
  RenderSettings settings;
};

// Unbiased and converging, through the engine's accumulation: 128 still frames (new seeds, 8x8 cuts, 4
// samples, raw) accumulated. Each frame's own estimate is N A_N - (N - 1) A_(N-1) from the accumulated means
// A; each pixel's mean of them equals the exact shadowed sum (every light, one ray each) within its standard
// error: summed over the pixels, the differences are within 4 standard errors of 0, and few pixels stray
// by more than 4 of theirs. The accumulated image's relative RMSE falls as frames^-1/2 (the log-log slope
// over 1, 4, 16 and 64 frames within 0.1 of -1/2): it converges to the exact image.
TEST_F(LightcutsFrameTest, AccumulatedFramesConvergeToTheExactShadowedSum) {
  settings.accumulation.enabled = true;
  const SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  constexpr int kFrames = 128;
  std::vector<double> sum, squares, previous, logFrames, logErrors;
  ImageRGBA exact;
  for (int frames = 1; frames <= kFrames; ++frames) {
    renderer.render(view());
    if (frames == 1) exact = exactIrradiance(renderer, &gpu);
    const ImageRGBA accumulated = renderer.readImage(Aov::Irradiance);
    const size_t pixels = accumulated.pixels.size();
    sum.resize(pixels, 0.0), squares.resize(pixels, 0.0), previous.resize(pixels, 0.0);
    for (size_t i = 0; i < pixels; ++i) {
      const double mean = luminance(glm::dvec3(accumulated.pixels[i]));
      const double frame = frames * mean - (frames - 1) * previous[i];
      sum[i] += frame, squares[i] += frame * frame, previous[i] = mean;
    }
    if (frames == 1 || frames == 4 || frames == 16 || frames == 64) {
      const double error = relativeRmse(accumulated, exact);
      std::printf("lightcuts: %d frames, relative RMSE %.4f\n", frames, error);
      logFrames.push_back(std::log(double(frames)));
      logErrors.push_back(std::log(error));
    }
  }
  double difference = 0, variance = 0;
  size_t compared = 0, strays = 0;
  for (size_t i = 0; i < sum.size(); ++i) {
    const double want = luminance(glm::dvec3(exact.pixels[i]));
    const double mean = sum[i] / kFrames;
    const double meanVariance = std::max(squares[i] / kFrames - mean * mean, 0.0) / (kFrames - 1);
    if (!(want > 0) || meanVariance <= 0) continue;
    ++compared;
    difference += mean - want;
    variance += meanVariance;
    if (std::abs(mean - want) > 4.0 * std::sqrt(meanVariance)) ++strays;
  }
  ASSERT_GT(compared, sum.size() / 2);
  const double z = difference / std::sqrt(variance);
  std::printf("lightcuts: %zu pixels, summed bias %.3g standard errors, %zu pixels beyond 4\n", compared, z, strays);
  EXPECT_LT(std::abs(z), 4.0) << "the frames' mean is off the exact shadowed sum";
  EXPECT_LT(double(strays), 0.01 * double(compared));
  // Least-squares slope of log error against log frames.
  const double count = double(logFrames.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < logFrames.size(); ++i) mx += logFrames[i] / count, my += logErrors[i] / count;
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < logFrames.size(); ++i)
    sxy += (logFrames[i] - mx) * (logErrors[i] - my), sxx += (logFrames[i] - mx) * (logFrames[i] - mx);
  EXPECT_NEAR(sxy / sxx, -0.5, 0.1);
}

// With 2x2 interleaving (2 samples per pixel from cuts of 8 nodes) one frame is not unbiased per pixel, but
// every 4 frames are (each pixel then takes every node of its block's cut once): the means of 32 groups of 4
// accumulated frames equal the exact shadowed sum within their standard error, summed over the pixels.
TEST_F(LightcutsFrameTest, InterleavedFramesAreUnbiasedOverTheirGroup) {
  settings.accumulation.enabled = true;
  settings.rtslc.samples = 2;
  settings.rtslc.interleave = 2;
  const SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  constexpr int kGroups = 32, kGroup = 4;
  std::vector<double> sum, squares, previous;
  ImageRGBA exact;
  for (int frames = 1; frames <= kGroups * kGroup; ++frames) {
    renderer.render(view());
    if (frames == 1) exact = exactIrradiance(renderer, &gpu);
    if (frames % kGroup != 0) continue;
    const ImageRGBA accumulated = renderer.readImage(Aov::Irradiance);
    sum.resize(accumulated.pixels.size(), 0.0), squares.resize(sum.size(), 0.0), previous.resize(sum.size(), 0.0);
    for (size_t i = 0; i < sum.size(); ++i) {
      const double mean = luminance(glm::dvec3(accumulated.pixels[i]));
      const double group = (frames * mean - (frames - kGroup) * previous[i]) / kGroup;  // this group's mean
      sum[i] += group, squares[i] += group * group, previous[i] = mean;
    }
  }
  double difference = 0, variance = 0;
  for (size_t i = 0; i < sum.size(); ++i) {
    const double want = luminance(glm::dvec3(exact.pixels[i])), mean = sum[i] / kGroups;
    const double meanVariance = std::max(squares[i] / kGroups - mean * mean, 0.0) / (kGroups - 1);
    if (!(want > 0) || meanVariance <= 0) continue;
    difference += mean - want;
    variance += meanVariance;
  }
  ASSERT_GT(variance, 0.0);
  const double z = difference / std::sqrt(variance);
  std::printf("lightcuts 2x2: summed bias %.3g standard errors over groups of 4 frames\n", z);
  EXPECT_LT(std::abs(z), 4.0);
}

// No input lights (no VPLs, no emitter samples): no tree, no cuts, a black indirect light and no NaN.
TEST_F(LightcutsFrameTest, NoLightsGiveNoIndirectLight) {
  settings.inputLights.vpls = 0;
  settings.inputLights.emitterSamples = 0;
  const SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  EXPECT_EQ(renderer.render(view()).nonFinitePixels, 0u);
  EXPECT_EQ(renderer.lightTree().leafCount, 0u);
  for (const glm::vec4& p : renderer.readImage(Aov::Irradiance).pixels) ASSERT_EQ(glm::vec3(p), glm::vec3(0.0f));
}

// Per-pixel cuts (B = 1: the representative is the pixel itself) against the CPU reference's greedy cut
// at each pixel's surface: every GPU cut partitions the lit lights, and all but a few (float against double
// where two nodes' bounds nearly tie) are the reference's cut, node for node.
TEST_F(LightcutsFrameTest, PerPixelCutsAreTheReferenceCuts) {
  settings.rtslc.blockSize = 1;
  settings.rtslc.samples = 12;
  const SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  renderer.render(view());
  const InputLights& s0 = renderer.inputLights();
  const std::vector<Light> lights = fromGpuLights(s0.lights.download<gpu::GpuLight>(s0.count));
  const LightTree cpu = buildLightTree(lights);
  glm::vec3 lower(lights[0].position), upper(lights[0].position);
  for (const Light& l : lights) lower = glm::min(lower, l.position), upper = glm::max(upper, l.position);
  // The authors' share of the lights' box, floored at the shading's clamp distance as rtslc.comp does.
  const double minDistance = std::max(double(settings.rtslc.errorLimit) * glm::length(glm::dvec3(upper - lower)),
                                      double(renderer.clampDistance()));

  RtslcPass pass;
  pass.selectCuts({gpu, renderer.gbuffer(), s0.lights, s0.count, renderer.lightTree()},
                  {settings.rtslc, renderer.clampDistance(), 1u});
  const std::vector<GLuint> cuts =
      pass.cuts().download<GLuint>(size_t(settings.image.width) * settings.image.height * gpu::kMaxCutNodes);
  const std::vector<glm::vec4> positions = renderer.gbuffer().position.readRGBA();
  const std::vector<glm::vec4> normals = renderer.gbuffer().normal.readRGBA();
  size_t surfaces = 0, same = 0;
  for (size_t pixel = 0; pixel < positions.size(); ++pixel) {
    if (positions[pixel].w == 0.0f) continue;
    ++surfaces;
    std::vector<uint32_t> cut;
    for (uint32_t i = 0; i < gpu::kMaxCutNodes; ++i)
      if (cuts[pixel * gpu::kMaxCutNodes + i] != gpu::kNoCutNode) cut.push_back(cuts[pixel * gpu::kMaxCutNodes + i]);
    ASSERT_FALSE(cut.empty());
    ASSERT_LE(cut.size(), size_t(settings.rtslc.samples));
    // A partition: every lit leaf lies under exactly one cut node.
    std::vector<int> covered(cpu.leafCount, 0);
    for (uint32_t node : cut) {
      uint32_t first = node, last = node;
      while (first < cpu.leafCount) first = 2 * first, last = 2 * last + 1;
      for (uint32_t leaf = first; leaf <= last; ++leaf) ++covered[leaf - cpu.leafCount];
    }
    for (uint32_t leaf = 0; leaf < cpu.leafCount; ++leaf)
      if (cpu.nodes[cpu.leafCount + leaf].intensity > 0) {
        ASSERT_EQ(covered[leaf], 1) << "pixel " << pixel;
      }
    const std::vector<uint32_t> want =
        selectCut(cpu, glm::dvec3(positions[pixel]), glm::dvec3(normals[pixel]), settings.rtslc.samples, minDistance);
    if (cut == want) ++same;
  }
  ASSERT_GT(surfaces, 0u);
  std::printf("lightcuts: %zu of %zu per-pixel cuts equal the reference's\n", same, surfaces);
  EXPECT_GE(double(same), 0.99 * double(surfaces));
}

}  // namespace
}  // namespace lgh::test
