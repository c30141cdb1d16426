// The lightcuts' variance-guided filter (glsl/irradiance_atrous.comp) and the variance estimates both
// filters trust, against what they claim:
//  * on a flat floor lit by many lights (pure sampling noise), the filtered lightcut image's error is at
//    most a third of the raw one's;
//  * across a depth step (a dark shelf over a lit floor) nothing bleeds: the shelf's pixels at its edge stay
//    dark;
//  * the ratio form (rtslc-denoiser ratio) splits the same samples: unfiltered, its unshadowed irradiance
//    times its ratio is the shadowed estimate pixel by pixel, and filtered it removes most of the noise;
//  * calibration: each pixel's variance estimate, averaged over many seeds, matches the spread of its
//    estimate across those seeds (0.8-1.25x), for the lightcuts' luminance (the filter's stage 0) and the
//    LGH's shadow-ray weight T (shadow_rays.comp: one sample's variance over k, so over k^2 in all).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <random>
#include <vector>

#include "exact_irradiance.h"
#include "gl_test_env.h"
#include "gltf_writer.h"
#include "render/image_compare.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

// A grey 12 x 12 floor under 300 point lights 0.5-3 m above it, their strengths spread over two decades (so
// that some samples are outliers), seen from 6 m above; with
// `shelf`, a dark-lit 2 x 2 shelf at 4 m facing up, every light below it (so its irradiance is 0).
// `rolling`: the floor is y = 0.4 sin(x) sin(z) with its smooth normals (up to 22 degrees from vertical).
std::filesystem::path writeLitFloor(const TempDir& dir, bool shelf, bool rolling = false) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 1}));
  if (rolling) {
    PrimitiveDesc floor;
    floor.material = grey;
    constexpr int kCells = 96;
    for (int j = 0; j <= kCells; ++j) {
      for (int i = 0; i <= kCells; ++i) {
        const float x = 12.0f * float(i) / kCells - 6.0f, z = 6.0f - 12.0f * float(j) / kCells;
        floor.positions.push_back({x, 0.4f * std::sin(x) * std::sin(z), z});
        floor.normals.push_back(
            glm::normalize(glm::vec3(-0.4f * std::cos(x) * std::sin(z), 1.0f, -0.4f * std::sin(x) * std::cos(z))));
      }
    }
    for (int j = 0; j < kCells; ++j) {
      for (int i = 0; i < kCells; ++i) {
        const uint32_t a = uint32_t(j * (kCells + 1) + i), b = a + 1, c = a + kCells + 1, d = c + 1;
        floor.indices.insert(floor.indices.end(), {a, b, d, a, d, c});
      }
    }
    w.addNode(NodeDesc{}.withMesh(w.addMesh({floor})));
  } else {
    w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({-6, 0, 6}, {12, 0, 0}, {0, 0, -12}, grey)})));
  }
  if (shelf) w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({-1, 4, 1}, {2, 0, 0}, {0, 0, -2}, grey)})));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 300; ++i)
    w.addNode(NodeDesc{}
                  .withLight(w.addLight(LightDesc{}.withIntensity(std::pow(10.0, 2.0 * unit(rng) - 1.0))))
                  .translated({14.0f * unit(rng) - 7.0f, 0.5f + 2.5f * unit(rng), 14.0f * unit(rng) - 7.0f}));
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("top").withYfov(1.2).withClip(0.1, 100)))
                .translated({0, 6, 0})
                .rotated(glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))));
  return w.write(dir / "floor.gltf");
}

class LightcutFilterTest : public GLTest {
 protected:
  LightcutFilterTest() {
    settings.image.width = 160;
    settings.image.height = 90;
    settings.inputLights.maxDirectLights = 0;  // the point lights are S0
    settings.inputLights.vpls = 0;
    settings.inputLights.emitterSamples = 0;
    settings.indirectMethod = IndirectMethod::Rtslc;
    settings.rtslc.samples = 4;
    settings.rtslc.blockSize = 8;
    settings.directShadows = false;
  }
  CameraView view(const Scene& scene) const {
    return makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  }
  TempDir dir;
  RenderSettings settings;
};

// One frame, raw (0 passes) and filtered (the default passes) from the same seed, against every light.
class LightcutFilterPatchTest : public LightcutFilterTest, public ::testing::WithParamInterface<bool> {};

TEST_P(LightcutFilterPatchTest, FilterRemovesMostOfTheNoise) {
  const Scene scene = loadScene(writeLitFloor(dir, false, GetParam()));
  const SceneGpu gpu(scene);
  RenderSettings raw = settings;
  raw.filter.passes = 0;
  Renderer rawRenderer(gpu, raw), filteredRenderer(gpu, settings);
  rawRenderer.render(view(scene));
  filteredRenderer.render(view(scene));
  const ImageRGBA exact = exactIrradiance(rawRenderer);
  const double rawError = relativeRmse(rawRenderer.readImage(Aov::Irradiance), exact);
  const double filteredError = relativeRmse(filteredRenderer.readImage(Aov::Irradiance), exact);
  std::printf("%s patch, n = 4: raw error %.4f, filtered %.4f (%.3fx)\n", GetParam() ? "rolling" : "flat", rawError,
              filteredError, filteredError / rawError);
  EXPECT_GT(rawError, 0.05) << "the raw estimate should be noisy here";
  EXPECT_LE(filteredError, rawError / 3.0);
}

INSTANTIATE_TEST_SUITE_P(FlatAndRolling, LightcutFilterPatchTest, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Rolling" : "Flat"; });

// The shelf's pixels (irradiance 0: every light is below it) stay dark up to its edge, over a floor lit
// all around it: the plane weight and the variance (0 on the shelf, from its own pixels) stop the taps.
TEST_F(LightcutFilterTest, FilterKeepsADepthStepSharp) {
  const Scene scene = loadScene(writeLitFloor(dir, true));
  const SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  renderer.render(view(scene));
  const ImageRGBA exact = exactIrradiance(renderer);
  const ImageRGBA filtered = renderer.readImage(Aov::Irradiance);
  const ImageRGBA position = renderer.readImage(Aov::Position);
  // The shelf's pixels within 2 of a floor pixel, and the floor's within 2 of a shelf pixel.
  auto onShelf = [&](int x, int y) { return position.at(x, y).y > 3.0f; };
  double shelfEdge = 0, floorEdge = 0;
  int shelfCount = 0, floorCount = 0;
  for (int y = 2; y < filtered.height - 2; ++y) {
    for (int x = 2; x < filtered.width - 2; ++x) {
      bool nearOther = false;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) nearOther |= onShelf(x + dx, y + dy) != onShelf(x, y);
      if (!nearOther) continue;
      if (onShelf(x, y)) {
        ASSERT_EQ(luminance(exact.at(x, y)), 0.0);
        shelfEdge += luminance(filtered.at(x, y)), ++shelfCount;
      } else {
        floorEdge += luminance(exact.at(x, y)), ++floorCount;
      }
    }
  }
  ASSERT_GT(shelfCount, 20);
  ASSERT_GT(floorCount, 20);
  shelfEdge /= shelfCount, floorEdge /= floorCount;
  std::printf("depth step: the shelf's edge %.4g against the floor's %.4g\n", shelfEdge, floorEdge);
  EXPECT_LT(shelfEdge, 0.01 * floorEdge);
}

// The ratio form's sums come from the same samples as the shadowed estimate (a ratio of sums, not of two
// estimates): unfiltered, U x (S / U) is S pixel by pixel; filtered, both forms lower the error against
// the exact shadowed irradiance by more than 3x in the Cornell box (shadows, colour bleeding, 4K VPLs).
TEST_F(LightcutFilterTest, RatioFormSplitsTheSameSamples) {
  const Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
  const SceneGpu gpu(scene);
  settings.inputLights.vpls = 4000;
  settings.inputLights.maxDirectLights = 8;
  RenderSettings raw = settings, ratio = settings, rawRatio = settings;
  raw.filter.passes = rawRatio.filter.passes = 0;
  ratio.rtslc.denoiser = rawRatio.rtslc.denoiser = RtslcDenoiser::Ratio;
  Renderer shadowed(gpu, raw), split(gpu, rawRatio), filtered(gpu, ratio);
  for (Renderer* r : {&shadowed, &split, &filtered}) r->render(view(scene));
  const ImageRGBA s = shadowed.readImage(Aov::Irradiance), u = split.readImage(Aov::Irradiance),
                  v = split.readImage(Aov::Visibility);
  double largest = 0, total = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      largest = std::max(largest, std::abs(luminance(u.at(x, y)) * v.at(x, y).r - luminance(s.at(x, y))));
      total += luminance(s.at(x, y));
    }
  }
  const double mean = total / double(s.width * s.height);
  const ImageRGBA exact = exactIrradiance(shadowed, &gpu);
  const double rawError = relativeRmse(s, exact);
  ImageRGBA product = filtered.readImage(Aov::Irradiance);
  const ImageRGBA visibility = filtered.readImage(Aov::Visibility);
  for (size_t i = 0; i < product.pixels.size(); ++i) product.pixels[i] *= visibility.pixels[i].r;
  const double ratioError = relativeRmse(product, exact);
  std::printf("ratio form: |U r - S| at most %.3g (mean S %.3g); error raw %.4f, filtered %.4f (%.3fx)\n", largest,
              mean, rawError, ratioError, ratioError / rawError);
  EXPECT_LT(largest, 1e-4 * mean);
  EXPECT_LE(ratioError, rawError / 3.0);
}

// Per pixel, the mean of the variance estimates over `frames` seeds and the variance of the estimates
// across them, summed over the pixels that have both (the sums compare the same pixels).
struct Calibration {
  double estimated = 0, measured = 0;
  double ratio() const { return estimated / measured; }
};

template <typename Sample>  // Sample(renderer) -> per pixel {estimate, its variance estimate}; NaN: skip
Calibration calibrate(Renderer& renderer, const CameraView& view, int frames, Sample sample) {
  std::vector<double> sum, squares, estimated;
  std::vector<int> counts;
  for (int f = 0; f < frames; ++f) {
    renderer.render(view);
    const std::vector<glm::dvec2> values = sample(renderer);
    sum.resize(values.size(), 0.0), squares.resize(values.size(), 0.0), estimated.resize(values.size(), 0.0);
    counts.resize(values.size(), 0);
    for (size_t i = 0; i < values.size(); ++i) {
      if (std::isnan(values[i].x)) continue;
      sum[i] += values[i].x, squares[i] += values[i].x * values[i].x, estimated[i] += values[i].y, ++counts[i];
    }
  }
  Calibration c;
  for (size_t i = 0; i < sum.size(); ++i) {
    if (counts[i] != frames) continue;
    const double mean = sum[i] / frames;
    c.measured += std::max(squares[i] / frames - mean * mean, 0.0) * frames / (frames - 1.0);
    c.estimated += estimated[i] / frames;
  }
  return c;
}

// The lightcuts' per-pixel luminance variance (the filter's stage 0, spatial: 7 x 7 neighbours on the same
// surface) over 64 seeds on the lit floor, against the spread of the raw luminance across the seeds.
TEST_F(LightcutFilterTest, LightcutVarianceMatchesTheSpreadAcrossSeeds) {
  const Scene scene = loadScene(writeLitFloor(dir, false));
  const SceneGpu gpu(scene);
  settings.filter.passes = 0;  // the output is stage 0's: the irradiance with its variance in alpha
  Renderer renderer(gpu, settings);
  const Calibration c = calibrate(renderer, view(scene), 64, [](const Renderer& r) {
    const ImageRGBA image = r.readImage(Aov::Irradiance);
    std::vector<glm::dvec2> values(image.pixels.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = {luminance(image.pixels[i]), image.pixels[i].a};
    return values;
  });
  std::printf("lightcuts: estimated / measured variance %.3f\n", c.ratio());
  EXPECT_GT(c.ratio(), 0.8);
  EXPECT_LT(c.ratio(), 1.25);
}

// The LGH's variance of its shadow-ray weight T = C mean(w) (the raw ratio's green and blue, k = 4, the
// Cornell box with its VPLs) over 64 seeds. With the prior off (correction sample spread 0) the estimate is
// the samples' own, sum (T_j - T)^2 / k^2 = ((k - 1) / k) var(T_j) / k: times k / (k - 1) it is unbiased.
// (The prior adds (spread C / k)^2, one sample's worth: see docs/measurements.md.)
TEST_F(LightcutFilterTest, ShadowRayVarianceMatchesTheSpreadAcrossSeeds) {
  const Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
  const SceneGpu gpu(scene);
  RenderSettings s;
  s.image.width = 160;
  s.image.height = 90;
  s.inputLights.vpls = 4000;
  s.shadows.samples = 4;
  s.shadows.correctionSampleSpread = 0.0f;
  Renderer renderer(gpu, s);
  const double k = s.shadows.samples;
  const Calibration c = calibrate(
      renderer, makeCameraView(resolveCamera(scene, s), s.image.width, s.image.height), 64, [&](const Renderer& r) {
        const gl::Texture2D& raw = r.texture(Aov::Ratio);  // readImage shows the ratio alone
        const ImageRGBA ratio = fromGLRows(raw.width(), raw.height(), raw.readRGBA());
        std::vector<glm::dvec2> values(ratio.pixels.size());
        for (size_t i = 0; i < values.size(); ++i)
          values[i] = ratio.pixels[i].b > 0.0f ? glm::dvec2(ratio.pixels[i].b, ratio.pixels[i].g * k / (k - 1.0))
                                               : glm::dvec2(std::nan(""));
        return values;
      });
  std::printf("LGH shadow rays: estimated / measured variance of T %.3f\n", c.ratio());
  EXPECT_GT(c.ratio(), 0.8);
  EXPECT_LT(c.ratio(), 1.25);
}

}  // namespace
}  // namespace lgh::test
