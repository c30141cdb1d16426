// The light pass against exact answers. The rasterized brute force (every S0 light full-screen) must
// equal the compute-shader sum; the LGH image must equal the CPU evaluator (lgh/evaluate.h) on the
// same hierarchy at the same surface points, and converge to the exact sum as alpha grows; the
// fragment counts and interleaving must account for every light exactly once.
#include <cmath>
#include <cstdio>

#include "exact_irradiance.h"
#include "gl_test_env.h"
#include "lgh/evaluate.h"
#include "render/image_compare.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"
#include "shared/lgh_types.h"

namespace lgh::test {
namespace {

struct SceneOnGpu {
  explicit SceneOnGpu(const std::filesystem::path& path) : scene(loadScene(path)), gpu(scene) {}
  Scene scene;
  SceneGpu gpu;
};

RenderSettings smallSettings(int vpls) {
  RenderSettings s;
  s.image.width = 160;
  s.image.height = 90;
  s.inputLights.vpls = vpls;
  s.inputLights.bounces = 2;
  s.inputLights.emitterSamples = 4096;
  s.shadows.samples = 0;  // these tests read the unshadowed irradiance
  return s;
}

struct Frame {
  ImageRGBA irradiance;
  FrameStats stats;
};

Frame renderIrradiance(Renderer& renderer, const Scene& scene) {
  const RenderSettings& s = renderer.settings();
  Frame f;
  f.stats = renderer.render(makeCameraView(resolveCamera(scene, s), s.image.width, s.image.height));
  EXPECT_EQ(f.stats.nonFinitePixels, 0u);
  f.irradiance = renderer.readImage(Aov::Irradiance);
  return f;
}

class LightPassTest : public GLTest {};

TEST_F(LightPassTest, RasterizedBruteForceEqualsComputeSum) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  RenderSettings settings = smallSettings(3000);
  settings.lightPass.bruteForce = true;
  settings.lightPass.overdraw = true;
  Renderer renderer(s.gpu, settings);
  const Frame raster = renderIrradiance(renderer, s.scene);
  const ImageRGBA exact = exactIrradiance(renderer);
  const double scale = meanLuminance(exact);
  ASSERT_GT(scale, 0.0);
  for (size_t i = 0; i < exact.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(raster.irradiance.pixels[i][k], exact.pixels[i][k], 1e-4 * (exact.pixels[i][k] + scale))
          << "pixel " << i;
  // Every light's full-screen triangle covers every pixel exactly once.
  EXPECT_DOUBLE_EQ(raster.stats.lights.rasterizedPerPixel, double(renderer.inputLights().count));
  EXPECT_EQ(raster.stats.lights.maxRasterized, unsigned(renderer.inputLights().count));
}

// The compute reference against the CPU's exact sum with more lights than llvmpipe lets one shader
// invocation loop over (65,535 iterations in all): every light must count.
TEST_F(LightPassTest, ComputeSumCountsEveryLight) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  RenderSettings settings = smallSettings(100000);
  settings.inputLights.bounces = 1;
  Renderer renderer(s.gpu, settings);
  renderIrradiance(renderer, s.scene);
  ASSERT_GT(renderer.inputLights().count, 70000u);
  const ImageRGBA exact = exactIrradiance(renderer);
  const ImageRGBA position = renderer.readImage(Aov::Position), normal = renderer.readImage(Aov::Normal);
  const std::vector<Light> lights =
      fromGpuLights(renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count));
  EvalOptions options;
  options.clampDistance = renderer.clampDistance();
  int checked = 0;
  for (size_t i = 0; i < position.pixels.size(); i += 311) {
    if (position.pixels[i].w == 0.0f) continue;
    const glm::dvec3 x(position.pixels[i]), n(normal.pixels[i]);
    const glm::dvec3 expected = evaluateExact(lights, x, &n, options);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(exact.pixels[i][k], expected[k], 1e-4 * expected[k] + 1e-9) << "pixel " << i;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

// Each pixel of the light pass equals lgh::evaluateHierarchy (double precision) at that pixel's
// surface, with the CPU S1+gather hierarchy built from the same input lights, for both first levels.
TEST_F(LightPassTest, MatchesCpuEvaluatorPixelByPixel) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  for (int firstLevel : {1, 0}) {
    SCOPED_TRACE("first level " + std::to_string(firstLevel));
    RenderSettings settings = smallSettings(4000);
    settings.lightPass.startLevel = firstLevel;
    settings.lightPass.alpha = 1.0f;
    Renderer renderer(s.gpu, settings);
    const Frame frame = renderIrradiance(renderer, s.scene);
    const ImageRGBA position = renderer.readImage(Aov::Position), normal = renderer.readImage(Aov::Normal);

    const std::vector<Light> lights =
        fromGpuLights(renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count));
    const Hierarchy cpu = buildGather(lights, renderer.hierarchy().grid);
    EvalOptions options;
    options.alpha = settings.lightPass.alpha;
    options.clampDistance = renderer.clampDistance();
    options.firstLevel = firstLevel;
    const double scale = meanLuminance(frame.irradiance);
    ASSERT_GT(scale, 0.0);
    int checked = 0;
    for (size_t i = 0; i < position.pixels.size(); i += 17) {
      if (position.pixels[i].w == 0.0f) continue;
      const glm::dvec3 x(position.pixels[i]), n(normal.pixels[i]);
      const glm::dvec3 expected = evaluateHierarchy(cpu, lights, x, &n, options);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(frame.irradiance.pixels[i][k], expected[k], 2e-3 * (expected[k] + scale)) << "pixel " << i;
      ++checked;
    }
    EXPECT_GT(checked, 300);
  }
}

// Relative RMSE of the LGH image against the exact sum for alpha = 0.5, 1, 2, 4 (docs/design.md §7).
//  * Start level 0 (S0 blended as the finest level): the error must fall with every step of alpha and
//    tends to zero (alpha -> infinity weights S0 alone). Measured at alpha = 2 on 160x90 with 20K-VPL
//    budgets and the default clamp: Cornell 0.048, Sponza 0.068, emissive Cornell 0.045; pinned at
//    0.08 (1.2-1.8x the measurements: a wrong radius, role or lobe moves it by far more, see the
//    alpha = 1 values).
//  * Start level 1 (the paper's default): alpha only moves the boundaries between levels; within R_1
//    the S1 clusters replace the VPLs, so the error falls to a plateau set by the S1 cell size
//    (measured 0.066 / 0.268 / 0.112 at alpha 2; smaller as the VPL count grows and S1 gets finer).
//    It must not grow with alpha, and alpha = 2 is pinned at 1.15x the measurement.
struct ConvergenceCase {
  const char* name;
  std::filesystem::path path;
  double startLevel1Alpha2Bound;
};

void expectConvergence(const ConvergenceCase& c) {
  SceneOnGpu s(c.path);
  RenderSettings settings = smallSettings(20000);
  Renderer renderer(s.gpu, settings);
  for (int startLevel : {0, 1}) {
    double previous = 1e30;
    for (float alpha : {0.5f, 1.0f, 2.0f, 4.0f}) {
      settings.lightPass.alpha = alpha;
      settings.lightPass.startLevel = startLevel;
      renderer.setSettings(settings);
      const Frame frame = renderIrradiance(renderer, s.scene);
      const double error = relativeRmse(frame.irradiance, exactIrradiance(renderer));
      std::printf("  %-8s start level %d  alpha %-4.3g relative RMSE %.4f  (%zu input lights, L = %d)\n", c.name,
                  startLevel, double(alpha), error, frame.stats.lights.inputLights, frame.stats.lights.levels);
      if (startLevel == 0) {
        EXPECT_LT(error, previous) << "alpha " << alpha;
        if (alpha == 2.0f) {
          EXPECT_LT(error, 0.08) << "start level 0";
        }
      } else {
        EXPECT_LT(error, previous * 1.001) << "alpha " << alpha;
        if (alpha == 2.0f) {
          EXPECT_LT(error, c.startLevel1Alpha2Bound) << "start level 1";
        }
      }
      previous = error;
    }
  }
}

TEST_F(LightPassTest, ErrorFallsWithAlphaOnCornellBox) {
  expectConvergence({"cornell", sourceDir() / "data/cornell_box.gltf", 0.076});
}

TEST_F(LightPassTest, ErrorFallsWithAlphaOnSponza) {
  LGH_REQUIRE_SHARED_SCENE(path, "sponza_sun/sponza_sun.gltf");
  expectConvergence({"sponza", path, 0.308});
}

TEST_F(LightPassTest, ErrorFallsWithAlphaOnEmissiveCornellBox) {
  LGH_REQUIRE_SHARED_SCENE(path, "cornell_emissive/cornell_emissive.gltf");
  expectConvergence({"emissive", path, 0.129});
}

// Interleaving draws each light into one of n^2 tiles with n^2 times its intensity: the image's
// mean (its energy) stays that of the 1x1 pass on a scene of smooth, large surfaces.
TEST_F(LightPassTest, InterleavingPreservesEnergy) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  RenderSettings settings = smallSettings(20000);
  settings.lightPass.overdraw = true;
  Renderer renderer(s.gpu, settings);
  const Frame reference = renderIrradiance(renderer, s.scene);
  const double referenceMean = meanLuminance(reference.irradiance);
  for (int n : {2, 4}) {
    settings.lightPass.interleave = n;
    renderer.setSettings(settings);
    const Frame frame = renderIrradiance(renderer, s.scene);
    const double mean = meanLuminance(frame.irradiance);
    std::printf(
        "  interleave %dx%d: mean %.6g vs %.6g (1x1), relative RMSE vs 1x1 %.4f, fragments/pixel %.1f vs %.1f\n", n, n,
        mean, referenceMean, relativeRmse(frame.irradiance, reference.irradiance),
        frame.stats.lights.rasterizedPerPixel, reference.stats.lights.rasterizedPerPixel);
    EXPECT_NEAR(mean, referenceMean, 0.01 * referenceMean) << n << "x" << n;
  }
}

// With n x n interleaving each brute-force light covers exactly one tile: every pixel is rasterized
// by lightCount / n^2 lights (to within one: the tiles' shares differ by one when n^2 does not divide
// the count), however the lights lie in the image.
TEST_F(LightPassTest, InterleavedBruteForceDrawsEachLightIntoOneTile) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  RenderSettings settings = smallSettings(0);
  settings.inputLights.emitterSamples = 0;
  settings.inputLights.vpls = 3200;
  settings.inputLights.bounces = 1;
  settings.lightPass.bruteForce = true;
  settings.lightPass.overdraw = true;
  settings.lightPass.interleave = 4;
  Renderer renderer(s.gpu, settings);
  const Frame frame = renderIrradiance(renderer, s.scene);
  const size_t count = renderer.inputLights().count;
  ASSERT_GT(count, 1000u);
  EXPECT_NEAR(frame.stats.lights.rasterizedPerPixel, double(count) / 16.0, 1.0);
  EXPECT_LE(frame.stats.lights.maxRasterized, unsigned((count + 15) / 16));
}

// Volume culling (screen octagons of the 2R spheres, depth-tested against the surfaces) skips only
// fragments whose blending weight is zero: the image equals the cube path's to 1e-4 per pixel, the
// fragments that shade are the same ones (same count), and fewer are rasterized. Checked at 1x1 and
// 4x4 (the tiles need their own depth), from S1 and from S0, and with the camera inside volumes, where
// the spheres around the camera are drawn as the far faces of icosahedra: with the whole viewport
// instead (at the sphere's far depth) the camera-inside case's efficiency was 0.55 and Sponza's 0.49;
// the icosahedra give 0.73 on both.
struct CullingCase {
  const char* name;
  int interleave, startLevel;
  float alpha;
  bool cameraInside;
  double minEfficiency = 0.0;  // shaded / rasterized fragments with culling
};

double maxRelativeDifference(const ImageRGBA& a, const ImageRGBA& b) {
  // Relative to the pixel, with a floor of 1e-6 of the image mean so that black pixels compare absolutely.
  const double floor = 1e-6 * meanLuminance(b);
  double worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int k = 0; k < 3; ++k)
      worst = std::max(
          worst, std::abs(double(a.pixels[i][k]) - b.pixels[i][k]) / std::max(std::abs(double(b.pixels[i][k])), floor));
  return worst;
}

void expectCullingKeepsTheImage(const SceneOnGpu& s, const CullingCase& c, int vpls) {
  SCOPED_TRACE(c.name);
  RenderSettings settings = smallSettings(vpls);
  settings.lightPass.interleave = c.interleave;
  settings.lightPass.startLevel = c.startLevel;
  settings.lightPass.alpha = c.alpha;
  settings.lightPass.overdraw = true;
  Camera camera = resolveCamera(s.scene, settings);
  if (c.cameraInside) {
    // Next to the back wall's centre (+z; the box opens towards -z), looking out through the box:
    // inside the volumes of the lights on that wall.
    const glm::vec3 centre = s.scene.bounds.center();
    camera.position = glm::vec3(centre.x, centre.y, s.scene.bounds.max.z - 0.02f * s.scene.bounds.diagonal());
    camera.orientation = glm::mat3(glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1));
    camera.znear = 1e-3f;
  }
  const CameraView view = makeCameraView(camera, settings.image.width, settings.image.height);
  settings.lightPass.volumeCulling = false;
  Renderer renderer(s.gpu, settings);
  const FrameStats cubes = renderer.render(view);
  const ImageRGBA cubeImage = renderer.readImage(Aov::Irradiance);
  settings.lightPass.volumeCulling = true;
  renderer.setSettings(settings);
  const FrameStats culled = renderer.render(view);
  const ImageRGBA culledImage = renderer.readImage(Aov::Irradiance);
  ASSERT_GT(meanLuminance(cubeImage), 0.0);
  const double difference = maxRelativeDifference(culledImage, cubeImage);
  std::printf(
      "  %s: fragments/px %.1f (cubes) -> %.1f (culled), shaded %.2f -> %.2f, efficiency %.2f -> %.2f, "
      "max relative difference %.2g\n",
      c.name, cubes.lights.rasterizedPerPixel, culled.lights.rasterizedPerPixel, cubes.lights.shadedPerPixel,
      culled.lights.shadedPerPixel, cubes.lights.efficiency(), culled.lights.efficiency(), difference);
  EXPECT_LE(difference, 1e-4);
  EXPECT_NEAR(culled.lights.shadedPerPixel, cubes.lights.shadedPerPixel, 1e-6 * cubes.lights.shadedPerPixel);
  EXPECT_LT(culled.lights.rasterizedPerPixel, cubes.lights.rasterizedPerPixel);
  EXPECT_LE(culled.lights.shadedPerPixel, culled.lights.rasterizedPerPixel);
  EXPECT_GE(culled.lights.efficiency(), c.minEfficiency);
}

TEST_F(LightPassTest, CulledVolumesShadeWhatCubesShade) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  for (const CullingCase& c :
       {CullingCase{"1x1 from S1", 1, 1, 1.0f, false}, CullingCase{"4x4 from S1", 4, 1, 1.0f, false},
        CullingCase{"2x2 from S0", 2, 0, 1.0f, false}, CullingCase{"camera inside, alpha 4", 1, 1, 4.0f, true, 0.65},
        CullingCase{"camera inside, 4x4 from S0", 4, 0, 2.0f, true}})
    expectCullingKeepsTheImage(s, c, 20000);
}

TEST_F(LightPassTest, CulledVolumesShadeWhatCubesShadeOnSponza) {
  LGH_REQUIRE_SHARED_SCENE(path, "sponza_sun/sponza_sun.gltf");
  SceneOnGpu s(path);
  for (const CullingCase& c :
       {CullingCase{"Sponza 1x1", 1, 1, 1.0f, false, 0.6}, CullingCase{"Sponza 4x4", 4, 1, 1.0f, false, 0.6}})
    expectCullingKeepsTheImage(s, c, 20000);
}

// A culled fragment has weight zero, so it cannot take part in shadow-sample selection: every pixel's
// importance total (the sum of the f of every fragment that offered itself) is the cube path's, with
// interleaving too. (The slots themselves differ: culled volumes are drawn sorted by depth slice, so
// the fragments of a pixel arrive in another order; the frequencies are checked by ShadowTest.)
TEST_F(LightPassTest, CullingLeavesShadowSelectionUnchanged) {
  SceneOnGpu s(sourceDir() / "data/cornell_box.gltf");
  for (int n : {1, 2}) {
    SCOPED_TRACE("interleave " + std::to_string(n));
    RenderSettings settings = smallSettings(20000);
    settings.shadows.samples = 4;
    settings.shadows.skipFinest = false;  // S1 lights are the ones culling touches most
    settings.lightPass.interleave = n;
    const CameraView view =
        makeCameraView(resolveCamera(s.scene, settings), settings.image.width, settings.image.height);
    std::vector<float> totals[2];
    std::vector<GLuint> slots[2];
    for (int culling : {0, 1}) {
      settings.lightPass.volumeCulling = culling == 1;
      Renderer renderer(s.gpu, settings);  // a fresh renderer: frame 0, the same seed
      renderer.render(view);
      const glm::ivec2 size = renderer.shadowSlots().size;
      const size_t pixels = size_t(size.x) * size_t(size.y);
      totals[culling] = renderer.shadowSlots().totals.download<float>(pixels);
      slots[culling] = renderer.shadowSlots().slots.download<GLuint>(pixels * 4);
    }
    size_t selected[2] = {0, 0};
    for (size_t i = 0; i < totals[0].size(); ++i)
      ASSERT_NEAR(totals[1][i], totals[0][i], 1e-5f * totals[0][i]) << "pixel " << i;
    for (int path : {0, 1})
      for (size_t i = 0; i < slots[path].size(); ++i) {
        selected[path] += slots[path][i] != gpu::kNoLight;
        // A slot is filled exactly where the pixel had some importance.
        ASSERT_EQ(slots[path][i] != gpu::kNoLight, totals[path][i / 4] > 0.0f) << "slot " << i;
      }
    EXPECT_GT(selected[0], slots[0].size() / 4);
    EXPECT_EQ(selected[1], selected[0]);
  }
}

}  // namespace
}  // namespace lgh::test
