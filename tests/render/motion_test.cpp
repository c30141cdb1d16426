// Motion: an animated scene followed frame by frame (poseScene, SceneGpu::follow) renders each frame as
// the still scene at that time does (the BVH, the emitters, S0 and the lights all follow); the VPLs are
// drawn from the same random numbers from frame to frame, so that a small move of the light moves them a
// little; and the history survives motion where the lighting did not change, and only there
// (AccumulationSettings::motion): a light switched off is gone at once, a moving occluder's shadow does
// not trail.
#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "exact_irradiance.h"
#include "gl_test_env.h"
#include "gltf_writer.h"
#include "render/image_compare.h"
#include "render/renderer.h"
#include "render/scene/added_lights.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/scripted_motion.h"
#include "shared/lgh_types.h"

namespace lgh::test {
namespace {

class MotionTest : public GLTest {
 protected:
  MotionTest() {
    settings.image.width = 96;
    settings.image.height = 54;
    settings.inputLights.vpls = 3000;
    settings.accumulation.enabled = true;
  }
  CameraView view(const Scene& scene) const {
    return makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  }
  RenderSettings settings;
};

// The largest difference of two images' pixels, over the larger image's brightest pixel.
double largestDifference(const ImageRGBA& a, const ImageRGBA& b) {
  double largest = 0.0, brightest = 1e-30;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      largest = std::max(largest, double(std::abs(a.pixels[i][c] - b.pixels[i][c])));
      brightest = std::max(brightest, double(std::max(a.pixels[i][c], b.pixels[i][c])));
    }
  return largest / brightest;
}

// Frames at 0, 0.7 and 1.3 s of data/cornell_moving_light.gltf (the lamp carried, the panel turning over
// the floor), followed from frame to frame, against the scene loaded anew and posed at 1.3 s before its
// first render: the same image to float round-off. A BVH not rebuilt leaves the panel's shadow where it
// was; S0 not rebuilt leaves the indirect light of the lamp's old place.
TEST_F(MotionTest, FollowedAnimationRendersEachFrameAsTheStillSceneAtItsTime) {
  const auto path = sourceDir() / "data" / "cornell_moving_light.gltf";
  settings.accumulation.enabled = false;  // each frame its own: the frames compared are the same frames
  Scene moving = loadScene(path);
  ASSERT_FALSE(moving.animation.empty());
  SceneGpu movingGpu(moving);
  EXPECT_EQ(movingGpu.bvh().quality, BvhQuality::High);
  Renderer followed(movingGpu, settings);
  FrameStats stats;
  for (double time : {0.0, 0.7, 1.3}) {
    movingGpu.follow(poseScene(moving, time));
    followed.restartRandomSequence();
    stats = followed.render(view(moving));
  }
  EXPECT_GT(stats.passMs(passes::kBvhBuild), 0.0) << "the moved panel's BVH build is reported with the passes";
  EXPECT_EQ(movingGpu.bvh().quality, kFollowBvhQuality) << "the rebuilds that follow motion are the faster ones";

  Scene still = loadScene(path);
  poseScene(still, 1.3);
  const SceneGpu stillGpu(still);
  Renderer fresh(stillGpu, settings);
  fresh.render(view(still));
  EXPECT_LT(largestDifference(followed.readImage(Aov::Final), fresh.readImage(Aov::Final)), 1e-4);
  // And the scene did move: the frame at 0 s differs.
  Scene start = loadScene(path);
  const SceneGpu startGpu(start);
  Renderer first(startGpu, settings);
  first.render(view(start));
  EXPECT_GT(largestDifference(first.readImage(Aov::Final), fresh.readImage(Aov::Final)), 0.05);
}

// A floor with a few blocks under a sun 40 degrees up: a 0.1 degree turn of the sun must move most VPLs
// a small fraction of the scene, because VPL i is drawn from the same random numbers in both frames. A
// path whose start moves across an edge (a block's rim, the floor's border) lands elsewhere: those jump.
// S0 is compacted (a path that leaves the scene deposits nothing), so a path that hits in one frame and
// misses in the other shifts the indices after it: VPL i is matched with the nearest of the other frame's
// VPLs within a window of indices as wide as that shift can be. VPLs redrawn from other random numbers
// (another seed) must fail the same measure, or the test would not be telling the two apart.
TEST_F(MotionTest, SunStepOfATenthOfADegreeMovesMostVplsALittle) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.6f, 0.6f, 0.6f, 1}));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({-5, 0, -5}, {10, 0, 0}, {0, 0, 10}, grey)})));
  for (int i = 0; i < 4; ++i) {
    const float height = 0.5f + 0.25f * float(i);
    w.addNode(NodeDesc{}.withMesh(
        w.addMesh({box({-3.0f + 2.0f * float(i), height, float(i % 2) - 0.5f}, {0.5f, height, 0.7f}, grey)})));
  }
  TempDir dir;
  Scene scene = loadScene(w.write(dir / "blocks.gltf"));
  addCommandLineLights(scene, {"30,40"}, {});
  SceneGpu gpu(scene);
  settings.inputLights.vpls = 20000;
  settings.inputLights.bounces = 2;
  Renderer renderer(gpu, settings);
  const std::vector<PunctualLight> start = scene.lights;
  Camera camera = resolveCamera(scene, settings);
  const auto vpls = [&](int frame) {
    gpu.follow(applyScriptedMotion(ScriptedMotion{{0.1f, 0.0f}, glm::vec3(0.0f), 0.0f}, frame, start, scene, camera));
    renderer.setSettings(settings);
    renderer.render(makeCameraView(camera, settings.image.width, settings.image.height));
    const InputLights& s0 = renderer.inputLights();
    return s0.lights.download<gpu::GpuLight>(s0.count);
  };
  const float near = 0.01f * scene.bounds.diagonal();
  // The fraction of `a`'s VPLs with one of `b`'s within `near`, among the indices a shift could reach.
  const auto closeFraction = [&](const std::vector<gpu::GpuLight>& a, const std::vector<gpu::GpuLight>& b) {
    const long window = 2 * std::abs(long(a.size()) - long(b.size())) + 16;
    size_t close = 0;
    for (long i = 0; i < long(a.size()); ++i) {
      float nearest = 1e30f;
      for (long j = std::max(0L, i - window); j < std::min(long(b.size()), i + window + 1); ++j)
        nearest = std::min(nearest, glm::length(b[size_t(j)].position - a[size_t(i)].position));
      close += nearest < near ? 1 : 0;
    }
    return double(close) / double(a.size());
  };
  const std::vector<gpu::GpuLight> before = vpls(0), after = vpls(1);
  ASSERT_GT(before.size(), 3000u);  // half the paths leave the open scene at once, half the rest after a bounce
  const double same = closeFraction(before, after);
  settings.inputLights.seed += 1;
  const double redrawn = closeFraction(after, vpls(1));
  std::printf(
      "0.1 degree sun step: %.1f%% of %zu VPLs moved less than 1%% of the scene's diagonal (%.3g); "
      "redrawn with another seed: %.1f%%\n",
      100.0 * same, before.size(), double(near), 100.0 * redrawn);
  EXPECT_GT(same, 0.9);
  EXPECT_LT(redrawn, 0.5);
}

// A light moved a centimetre after 8 still frames (the viewer's panel does this): the history AOV shows the
// pixels that kept their frames (9 now) and those that started anew; most keep them, because the lighting
// at most surfaces barely changed. With accumulate-motion restart, none does.
TEST_F(MotionTest, SmallLightMoveKeepsMostPixelsHistoryShownAsTheHistoryAov) {
  for (HistoryMotion motion : {HistoryMotion::Gradient, HistoryMotion::Restart}) {
    Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
    SceneGpu gpu(scene);
    settings.accumulation.motion = motion;
    Renderer renderer(gpu, settings);
    for (int f = 0; f < 8; ++f) renderer.render(view(scene));
    PunctualLight moved = gpu.lights()[0];
    moved.position.x += 0.01f;
    gpu.setPunctualLight(0, moved);
    renderer.render(view(scene));
    const std::vector<glm::vec4> history = renderer.texture(Aov::History).readRGBA();
    const std::vector<glm::vec4> position = renderer.gbuffer().position.readRGBA();
    size_t valid = 0, kept = 0;
    for (size_t i = 0; i < history.size(); ++i) {
      if (position[i].w <= 0) continue;
      ++valid;
      kept += history[i].a > 8.5f ? 1 : 0;
    }
    const double share = double(kept) / double(std::max<size_t>(valid, 1));
    std::printf("history after a 1 cm light move (%s): %.1f%% of the pixels kept their 8 frames\n",
                motion == HistoryMotion::Gradient ? "gradient" : "restart", 100.0 * share);
    if (motion == HistoryMotion::Gradient)
      EXPECT_GT(share, 0.8);
    else
      EXPECT_EQ(kept, 0u);
    const ImageRGBA shown = renderer.readImage(Aov::History);  // a heat map over the longest history
    EXPECT_GT(meanLuminance(shown), 0.0);
  }
  // The lightcuts' history shows too (their moments' alpha): 2 frames after 2 still ones.
  Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
  const SceneGpu gpu(scene);
  settings.indirectMethod = IndirectMethod::Rtslc;
  Renderer lightcuts(gpu, settings);
  for (int f = 0; f < 2; ++f) lightcuts.render(view(scene));
  float longest = 0.0f;
  for (const glm::vec4& p : lightcuts.texture(Aov::History).readRGBA()) longest = std::max(longest, p.a);
  EXPECT_EQ(longest, 2.0f);
}

// The relative RMSE of the renderer's last shadowed indirect irradiance against the exact one of its frame
// (every VPL of its S0 at every pixel, with a shadow ray each).
double shadowedError(const Renderer& renderer, const SceneGpu& gpu) {
  return relativeRmse(shadowedIrradiance(renderer), exactIrradiance(renderer, &gpu));
}

// The lamp of the Cornell box switched off after 8 still frames: its indirect light must be gone in the
// very next frame in every history mode (a kept history would hold 8 / 9 of it).
TEST_F(MotionTest, LightSwitchedOffTakesItsIndirectLightWithIt) {
  for (HistoryMotion motion : {HistoryMotion::Gradient, HistoryMotion::Ratio, HistoryMotion::Restart}) {
    SCOPED_TRACE(int(motion));
    Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
    SceneGpu gpu(scene);
    settings.accumulation.motion = motion;
    Renderer renderer(gpu, settings);
    for (int f = 0; f < 8; ++f) renderer.render(view(scene));
    EXPECT_GT(meanLuminance(renderer.readImage(Aov::Irradiance)), 0.0);
    PunctualLight off = gpu.lights()[0];
    off.intensity = glm::vec3(0.0f);
    gpu.setPunctualLight(0, off);
    renderer.render(view(scene));
    EXPECT_EQ(meanLuminance(renderer.readImage(Aov::Irradiance)), 0.0) << "within 1 frame";
  }
}

// accumulate-motion keep (SVGF's temporal accumulation, the lightcuts paper's): the history is kept whatever
// changed, an exponential moving average of weight 1 / maxFrames. The lamp switched off after 8 still
// frames with a history of 5: the irradiance is 4/5 of the still one the next frame and 16/25 the frame
// after (whole irradiance, the same at every pixel's mean). The other modes drop it at once (above).
TEST_F(MotionTest, KeepHoldsTheHistoryThroughMotionAsAMovingAverageOfMaxFrames) {
  Scene scene = loadScene(sourceDir() / "data" / "cornell_box.gltf");
  SceneGpu gpu(scene);
  settings.accumulation.motion = HistoryMotion::Keep;
  settings.accumulation.maxFrames = 5;
  Renderer renderer(gpu, settings);
  for (int f = 0; f < 8; ++f) renderer.render(view(scene));
  const double still = meanLuminance(renderer.readImage(Aov::Irradiance));
  ASSERT_GT(still, 0.0);
  PunctualLight off = gpu.lights()[0];
  off.intensity = glm::vec3(0.0f);
  gpu.setPunctualLight(0, off);
  renderer.render(view(scene));
  EXPECT_NEAR(meanLuminance(renderer.readImage(Aov::Irradiance)) / still, 0.8, 1e-4);
  renderer.render(view(scene));
  EXPECT_NEAR(meanLuminance(renderer.readImage(Aov::Irradiance)) / still, 0.64, 1e-4);
}

// data/cornell_moving_light.gltf's panel slides and turns over the floor: 12 frames at 24 frames a second
// from 0.4 s with the history kept where each pixel's tests allow (the default, kMotionGradient), the lamp
// carried too or held where it starts. The shadowed error of the last frame against the exact irradiance of
// that frame, beside the same 12 frames rendered still at the last pose and one frame without history.
struct TrailErrors {
  double moving = 0, still = 0, oneFrame = 0;
};

// The frames at `times` followed with history, against `stills` frames rendered still at the last time.
TrailErrors trailErrors(RenderSettings settings, bool lampMoves, const std::vector<double>& times, int stills) {
  const auto path = sourceDir() / "data" / "cornell_moving_light.gltf";
  const int kFrames = int(times.size());
  const auto timeOf = [&](int f) { return times[size_t(f)]; };
  const auto viewOf = [&](const Scene& scene) {
    return makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  };
  TrailErrors errors;
  Scene moving = loadScene(path);
  poseScene(moving, timeOf(0));
  const PunctualLight lampAtStart = moving.lights[0];
  SceneGpu movingGpu(moving);
  Renderer followed(movingGpu, settings);
  for (int f = 0; f < kFrames; ++f) {
    PoseChange change = poseScene(moving, timeOf(f));
    if (!lampMoves) {
      moving.lights[0] = lampAtStart;
      change.lights.clear();
    }
    movingGpu.follow(change);
    followed.render(viewOf(moving));
  }
  errors.moving = shadowedError(followed, movingGpu);

  Scene still = loadScene(path);
  poseScene(still, timeOf(kFrames - 1));
  if (!lampMoves) still.lights[0] = lampAtStart;
  const SceneGpu stillGpu(still);
  Renderer accumulated(stillGpu, settings);
  for (int f = 0; f < stills; ++f) accumulated.render(viewOf(still));
  errors.still = shadowedError(accumulated, stillGpu);
  settings.accumulation.enabled = false;
  Renderer oneFrame(stillGpu, settings);
  oneFrame.render(viewOf(still));
  errors.oneFrame = shadowedError(oneFrame, stillGpu);
  std::printf(
      "shadowed error at the last of %d frames, lamp %s: moving with history %.4f, still %.4f, one frame "
      "%.4f\n",
      kFrames, lampMoves ? "carried" : "held", errors.moving, errors.still, errors.oneFrame);
  return errors;
}

// 12 frames at 24 frames a second from 0.4 s.
TrailErrors trailErrors(const RenderSettings& settings, bool lampMoves) {
  std::vector<double> times;
  for (int f = 0; f < 12; ++f) times.push_back(0.4 + f / 24.0);
  return trailErrors(settings, lampMoves, times, 12);
}

// The panel moves, the lamp is held: the history is kept away from the panel and its shadow, so the last
// frame's error is as the still frames' (measured 0.139 and 0.139; one frame 0.170). A history kept whole,
// its tests off, trails the panel's shadow: 0.226, 1.63x.
TEST_F(MotionTest, MovingOccluderKeepsTheHistoryAroundItsShadowWithoutTrailingIt) {
  settings.shadows.samples = 2;
  const TrailErrors e = trailErrors(settings, false);
  EXPECT_LT(e.moving, e.oneFrame);
  EXPECT_LT(e.moving, 1.15 * e.still);
}

// The lamp is carried too: the lighting changes everywhere every frame; the irradiance's history gives way
// to each frame's and the ratio's stays where the shadows do, so the error stays near the still frames'
// (measured 1.04x; one frame 1.16x). A history kept whole, its tests off, 1.81x; the irradiance replaced
// without its ratio weights scaled with it (the mean weight D then mixes frames), 1.18x.
TEST_F(MotionTest, MovingLampDoesNotTrailItsLight) {
  settings.shadows.samples = 2;
  const TrailErrors e = trailErrors(settings, true);
  EXPECT_LT(e.moving, e.oneFrame);
  EXPECT_LT(e.moving, 1.15 * e.still);
}

// A spot lights the back wall (one bounce: the VPLs lie on the wall alone); a panel the spot does not reach
// hangs over the floor and jumps from one side to the other after 8 still frames. The VPLs and the floor's
// unshadowed irradiance stay exactly as they were; only the panel's indirect shadow on the floor moves, which
// the irradiance's gradient cannot see and the ratio's test must: the frame after the jump has to be as good
// as one frame rendered there from scratch: within 1.2x (measured 1.12x; with the ratio's test off, the old
// shadow stays and the new one is 1/9 there: 3.2x).
TEST_F(MotionTest, JumpingOccluderTakesItsIndirectShadowWithIt) {
  GltfWriter w;
  const int white = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.8f, 0.8f, 1}).twoSided());
  w.addNode(NodeDesc{}.withMesh(
      w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, white), quad({-2, 0, -2}, {4, 0, 0}, {0, 3, 0}, white)})));
  const int panel = w.addNode(NodeDesc{}
                                  .named("panel")
                                  .withMesh(w.addMesh({quad({-0.6f, 0, 0.6f}, {1.2f, 0, 0}, {0, 0, -1.2f}, white)}))
                                  .translated({-1, 0.9, -1.1}));
  const glm::quat towardsWall = glm::angleAxis(glm::radians(-12.0f), glm::vec3(1, 0, 0));
  w.addNode(NodeDesc{}
                .withLight(w.addLight(LightDesc{}.ofType("spot").withIntensity(40).withCone(0.0, 0.3)))
                .translated({0, 2.6, 1})
                .rotated(towardsWall));
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("above")))
                .translated({0, 3.5, 3})
                .rotated(glm::angleAxis(glm::radians(-45.0f), glm::vec3(1, 0, 0))));
  w.addAnimationChannel(panel, "translation", {0, 1}, {-1, 0.9f, -1.1f, 1, 0.9f, -1.1f}, "STEP");
  TempDir dir;
  const auto path = w.write(dir / "jump.gltf");
  settings.shadows.samples = 2;
  settings.inputLights.bounces = 1;

  Scene scene = loadScene(path);
  poseScene(scene, 0.0);
  SceneGpu gpu(scene);
  Renderer followed(gpu, settings);
  for (int f = 0; f < 8; ++f) followed.render(view(scene));
  const size_t vplsBefore = followed.inputLights().count;
  gpu.follow(poseScene(scene, 1.0));
  followed.render(view(scene));
  ASSERT_EQ(followed.inputLights().count, vplsBefore) << "the panel must stay out of the spot's light";
  const double jumped = shadowedError(followed, gpu);

  Scene still = loadScene(path);
  poseScene(still, 1.0);
  const SceneGpu stillGpu(still);
  RenderSettings single = settings;
  single.accumulation.enabled = false;
  Renderer oneFrame(stillGpu, single);
  oneFrame.render(view(still));
  const double fresh = shadowedError(oneFrame, stillGpu);
  std::printf("the frame after the panel's jump: error %.4f; one frame rendered there %.4f\n", jumped, fresh);
  EXPECT_LT(jumped, 1.2 * fresh);
}

}  // namespace
}  // namespace lgh::test
