// Moving or recolouring a punctual light after the scene is on the GPU (SceneGpu::setPunctualLight,
// the viewer's light editing): the renderer must notice, rebuild the VPLs and the hierarchy from the
// new light, and light the scene as a scene loaded with that light would.
#include "gl_test_env.h"
#include "render/image_compare.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

class LightEditTest : public GLTest {
 protected:
  LightEditTest() : scene(loadScene(sourceDir() / "data" / "cornell_box.gltf")) {
    settings.image.width = 96;
    settings.image.height = 54;
    settings.inputLights.vpls = 3000;
    settings.shadows.samples = 0;  // no per-frame shadow sampling: frames of the same lights are equal
  }
  CameraView view() const {
    return makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  }

  Scene scene;
  RenderSettings settings;
};

TEST_F(LightEditTest, ChangedLightRebuildsVplsAndHierarchy) {
  ASSERT_FALSE(scene.lights.empty());
  SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  EXPECT_TRUE(renderer.render(view()).lightsRebuilt);
  const ImageRGBA indirect = renderer.readImage(Aov::Indirect), direct = renderer.readImage(Aov::Direct);
  EXPECT_FALSE(renderer.render(view()).lightsRebuilt) << "nothing changed, nothing to rebuild";

  // Twice the intensity: twice the direct and (one light, so the same paths) twice the VPLs' flux.
  const PunctualLight original = gpu.lights()[0];
  PunctualLight brighter = original;
  brighter.intensity *= 2.0f;
  const unsigned version = gpu.lightsVersion();
  gpu.setPunctualLight(0, brighter);
  EXPECT_NE(gpu.lightsVersion(), version);
  EXPECT_TRUE(renderer.render(view()).lightsRebuilt);
  EXPECT_NEAR(meanLuminance(renderer.readImage(Aov::Direct)) / meanLuminance(direct), 2.0, 1e-4);
  EXPECT_NEAR(meanLuminance(renderer.readImage(Aov::Indirect)) / meanLuminance(indirect), 2.0, 1e-3);

  // Moved down by a fifth of the box: a different image, direct and indirect.
  PunctualLight moved = original;
  moved.position.y -= 0.2f * scene.bounds.extent().y;
  gpu.setPunctualLight(0, moved);
  EXPECT_TRUE(renderer.render(view()).lightsRebuilt);
  EXPECT_GT(relativeRmse(renderer.readImage(Aov::Direct), direct), 0.05);
  EXPECT_GT(relativeRmse(renderer.readImage(Aov::Indirect), indirect), 0.05);

  // Back where it was: the first frame again (same seed, same VPLs; only float summation order may vary).
  gpu.setPunctualLight(0, original);
  EXPECT_TRUE(renderer.render(view()).lightsRebuilt);
  EXPECT_LT(relativeRmse(renderer.readImage(Aov::Direct), direct), 1e-6);
  EXPECT_LT(relativeRmse(renderer.readImage(Aov::Indirect), indirect), 1e-4);
}

// Levels changed while brute force is on (no hierarchy drawn) must be built once brute force is off.
TEST_F(LightEditTest, LevelsChangedDuringBruteForceAreBuilt) {
  SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  renderer.render(view());
  const int automatic = renderer.hierarchy().grid.levels;
  const int requested = automatic > 2 ? automatic - 1 : automatic + 1;
  RenderSettings s = settings;
  s.lightPass.bruteForce = true;
  s.hierarchy.levels = requested;
  renderer.setSettings(s);
  EXPECT_FALSE(renderer.render(view()).lightsRebuilt) << "brute force needs no hierarchy";
  s.lightPass.bruteForce = false;
  renderer.setSettings(s);
  EXPECT_TRUE(renderer.render(view()).lightsRebuilt);
  EXPECT_EQ(renderer.hierarchy().grid.levels, requested);
}

TEST_F(LightEditTest, LightIndexOutOfRangeThrows) {
  SceneGpu gpu(scene);
  EXPECT_THROW(gpu.setPunctualLight(gpu.lights().size(), PunctualLight{}), std::out_of_range);
}

}  // namespace
}  // namespace lgh::test
