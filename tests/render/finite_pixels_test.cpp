// Frames stay finite where an estimate meets denormals. llvmpipe flushes denormals in arithmetic but not
// in comparisons, so a guard "x > 0 ? y / x" can still divide 0 by 0. Two frames on the shipped Cornell box
// (../shared/scenes) that did: the LGH at alpha 0.5, 4x4, raw (a tile whose irradiance is denormal under
// samples that see light: its mean weight D infinite, its variance 0 / 0; 1 NaN pixel), and the stochastic
// lightcuts at 1 sample, 4x4, filtered (two all but black taps' relative luminance difference 0 / 0 in
// the filter's second pass, spread to 841 pixels by the next ones).
#include "gl_test_env.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

class FinitePixelsTest : public GLTest {
 protected:
  static RenderSettings settings() {
    RenderSettings s;
    s.image.width = 320;
    s.image.height = 180;
    s.inputLights.vpls = 13000;
    return s;
  }
  static unsigned nonFinitePixels(const Scene& scene, const RenderSettings& s) {
    const SceneGpu gpu(scene);
    Renderer renderer(gpu, s);
    return renderer.render(makeCameraView(resolveCamera(scene, s), s.image.width, s.image.height)).nonFinitePixels;
  }
};

TEST_F(FinitePixelsTest, InterleavedRawLghFrameWithDenormalTiles) {
  LGH_REQUIRE_SHARED_SCENE(path, "cornell_emissive/cornell_emissive.gltf");
  const Scene scene = loadScene(path);
  RenderSettings s = settings();
  s.lightPass.alpha = 0.5f;
  s.lightPass.interleave = 4;
  s.filter.passes = 0;
  EXPECT_EQ(nonFinitePixels(scene, s), 0u);
}

TEST_F(FinitePixelsTest, InterleavedFilteredLightcutsFrame) {
  LGH_REQUIRE_SHARED_SCENE(path, "cornell_emissive/cornell_emissive.gltf");
  const Scene scene = loadScene(path);
  RenderSettings s = settings();
  s.indirectMethod = IndirectMethod::Rtslc;
  s.rtslc.samples = 1;
  s.rtslc.interleave = 4;
  EXPECT_EQ(nonFinitePixels(scene, s), 0u);
}

}  // namespace
}  // namespace lgh::test
