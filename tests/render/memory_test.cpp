// GPU memory accounting (render/gl/memory.h): the registry sums exactly what the GL objects allocate,
// frees it with them, and a frame holds only what its configuration uses: constant over a long run, the
// same again after a round trip through another method or size, the hierarchy's bytes following the
// lights rather than the scene's extent, the shadow sampling's bytes per pixel fixed (the LGH paper's
// fixed footprint), and a request past the budget refused by name before the driver sees it.
#include "render/gl/memory.h"

#include <random>

#include "gl_test_env.h"
#include "render/gl/buffer.h"
#include "render/gl/texture.h"
#include "render/passes/lgh_build_pass.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

using gl::memory;

size_t ownerBytes(const char* owner) { return memory().ownerBytes(owner); }

TEST_F(GLTest, MemoryRegistryCountsExactlyWhatIsAllocatedAndFreed) {
  const size_t before = memory().liveBytes();
  {
    gl::Buffer buffer({"test", "buffer"}, 1000);
    EXPECT_EQ(memory().liveBytes() - before, 1000u);
    // RGBA32F 16 x 8 and R32F 64 x 32 with its whole mip chain (2048 + 4 x (2048 + 512 + ... + 1)).
    gl::Texture2D texture({"test", "texture"}, 16, 8, GL_RGBA32F);
    gl::Texture2D mipmapped({"test", "mipmapped"}, 64, 32, GL_R32F, 7);
    const size_t mips = 4 * (2048 + 512 + 128 + 32 + 8 + 2 + 1);
    EXPECT_EQ(memory().liveBytes() - before, 1000u + 2048u + mips);
    EXPECT_EQ(ownerBytes("test"), 1000u + 2048u + mips);
    // A moved object is counted once; a replaced one is gone.
    gl::Buffer moved = std::move(buffer);
    EXPECT_EQ(ownerBytes("test"), 1000u + 2048u + mips);
    moved = gl::Buffer({"test", "smaller"}, 12);
    EXPECT_EQ(ownerBytes("test"), 12u + 2048u + mips);
    // Zero bytes is a 16-byte stub in GL, and counted as such.
    gl::Buffer empty({"test", "empty"}, 0);
    EXPECT_EQ(ownerBytes("test"), 28u + 2048u + mips);
    bool listed = false;
    for (const auto& o : memory().byOwner()) listed |= o.owner == "test" && o.objects == 4;
    EXPECT_TRUE(listed) << "byOwner() lists the test's four objects under their owner";
    EXPECT_GE(memory().peakBytes(), before + 1000u + 2048u + mips);
  }
  EXPECT_EQ(memory().liveBytes(), before);
  EXPECT_EQ(ownerBytes("test"), 0u);
}

TEST_F(GLTest, MemoryPastTheLimitIsRefusedByNameBeforeAnyStorage) {
  const size_t before = memory().liveBytes();
  memory().setLimit(before + 4096);
  gl::Buffer fits({"test", "fits"}, 4000);
  try {
    gl::Buffer tooLarge({"test", "too large", "the test's setting"}, 200);
    ADD_FAILURE() << "a buffer past the limit was allocated";
  } catch (const gl::OutOfMemory& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("test: too large"), std::string::npos) << message;
    EXPECT_NE(message.find("the test's setting"), std::string::npos) << message;
    EXPECT_NE(message.find("200 B"), std::string::npos) << message;
    EXPECT_NE(message.find("gpu-memory-limit"), std::string::npos) << message;
  }
  EXPECT_THROW(gl::Texture2D({"test", "texture"}, 64, 64, GL_RGBA32F), gl::OutOfMemory);
  EXPECT_EQ(memory().liveBytes(), before + 4000) << "nothing refused is counted";
  memory().setLimit(0);
}

TEST_F(GLTest, StorageBindingLargerThanOneBlockIsRefusedByName) {
  const size_t block = gl::maxStorageBlockBytes();
  if (block > (size_t(1) << 30)) GTEST_SKIP() << "this device's storage blocks (" << block << " bytes) are too large";
  gl::Buffer large({"test", "large", "the test's setting"}, block + 256);
  large.bindRange(GL_SHADER_STORAGE_BUFFER, 0, 0, block);  // a chunk of at most one block binds
  try {
    large.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    ADD_FAILURE() << "a binding longer than a storage block went through";
  } catch (const gl::OutOfMemory& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("test: large"), std::string::npos) << message;
    EXPECT_NE(message.find("the test's setting"), std::string::npos) << message;
    EXPECT_NE(message.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << message;
  }
}

class FrameMemoryTest : public GLTest {
 protected:
  FrameMemoryTest() : scene(loadScene(sourceDir() / "data" / "cornell_box.gltf")) {
    settings.image.width = 160;
    settings.image.height = 90;
    settings.inputLights.vpls = 4000;
    settings.shadows.samples = 4;
  }
  CameraView view() const {
    return makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  }
  // Renders `frames` frames with `s` and returns the bytes held after them.
  size_t heldAfter(Renderer& renderer, const RenderSettings& s, int frames = 2) {
    settings = s;
    renderer.setSettings(s);
    for (int f = 0; f < frames; ++f) renderer.render(view());
    return memory().liveBytes();
  }

  Scene scene;
  RenderSettings settings;
};

constexpr const char* kLghOwners[] = {passes::kLghBuild, passes::kLightPass, passes::kShadowTargets,
                                      passes::kShadowRays, passes::kShadowFilter};
constexpr const char* kLightcutOwners[] = {passes::kLightTreeBuild, passes::kLightcutCuts, passes::kLightcutSampling,
                                           passes::kIrradianceFilter};

TEST_F(FrameMemoryTest, ALongRunHoldsConstantMemory) {
  settings.accumulation.enabled = true;
  settings.lightPass.interleave = 2;
  for (const char* method : {"lgh", "rtslc"}) {
    SCOPED_TRACE(method);
    settings.indirectMethod = choiceValue<IndirectMethod>(method, kIndirectMethodChoices);
    SceneGpu gpu(scene);
    Renderer renderer(gpu, settings);
    for (int f = 0; f < 3; ++f) renderer.render(view());
    const size_t held = memory().liveBytes();
    memory().resetPeak();
    for (int f = 0; f < 100; ++f) renderer.render(view());
    EXPECT_EQ(memory().liveBytes(), held);
    EXPECT_EQ(memory().peakBytes(), held) << "a still frame allocates nothing, not even for a moment";
  }
}

TEST_F(FrameMemoryTest, SwitchingMethodOrSizeComesBackToTheSameBytes) {
  SceneGpu gpu(scene);
  const size_t sceneBytes = memory().liveBytes();
  Renderer renderer(gpu, settings);
  RenderSettings lgh = settings, rtslc = settings;
  rtslc.indirectMethod = IndirectMethod::Rtslc;
  const size_t lghBytes = heldAfter(renderer, lgh);
  for (const char* owner : kLightcutOwners) EXPECT_EQ(ownerBytes(owner), 0u) << owner << " while the LGH runs";
  heldAfter(renderer, rtslc);
  for (const char* owner : kLghOwners) EXPECT_EQ(ownerBytes(owner), 0u) << owner << " while the lightcuts run";
  EXPECT_GT(ownerBytes(passes::kLightTreeBuild), 0u);
  EXPECT_EQ(heldAfter(renderer, lgh), lghBytes) << "lgh -> rtslc -> lgh";

  RenderSettings small = settings, large = settings;
  small.image.width = 320;
  small.image.height = 180;
  large.image.width = 640;
  large.image.height = 360;
  const size_t smallBytes = heldAfter(renderer, small);
  const size_t largeBytes = heldAfter(renderer, large);
  EXPECT_EQ(heldAfter(renderer, small), smallBytes) << "320x180 -> 640x360 -> 320x180";
  // The image's part scales with the pixels: 4x as many, 4x the bytes above the scene and the lights.
  const size_t lightBytes = ownerBytes(passes::kInputLights) + ownerBytes(passes::kLghBuild);
  const double perPixelSmall = double(smallBytes - sceneBytes - lightBytes) / (320.0 * 180.0);
  const double perPixelLarge = double(largeBytes - sceneBytes - lightBytes) / (640.0 * 360.0);
  EXPECT_NEAR(perPixelLarge / perPixelSmall, 1.0, 0.02);
}

TEST_F(FrameMemoryTest, FeaturesThatAreOffHoldNothing) {
  SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  RenderSettings accumulating = settings, still = settings, unshadowed = settings, noIndirect = settings;
  accumulating.accumulation.enabled = true;
  unshadowed.shadows.samples = 0;
  noIndirect.indirectMethod = IndirectMethod::None;
  heldAfter(renderer, accumulating);
  EXPECT_GT(ownerBytes(passes::kAccumulation), 0u);
  const size_t stillBytes = heldAfter(renderer, still);
  EXPECT_EQ(ownerBytes(passes::kAccumulation), 0u) << "the history while accumulation is off";
  EXPECT_GT(ownerBytes(passes::kShadowRays), 0u);
  heldAfter(renderer, unshadowed);
  for (const char* owner : {passes::kShadowTargets, passes::kShadowRays, passes::kShadowFilter})
    EXPECT_EQ(ownerBytes(owner), 0u) << owner << " without shadow rays";
  EXPECT_LT(memory().liveBytes(), stillBytes);
  RenderSettings bruteForce = unshadowed;
  bruteForce.lightPass.bruteForce = true;
  heldAfter(renderer, bruteForce, 1);
  EXPECT_EQ(ownerBytes(passes::kLghBuild), 0u) << "the hierarchy while brute force draws S0";
  heldAfter(renderer, noIndirect, 1);
  for (const char* owner : {passes::kLightPass, passes::kLghBuild, passes::kShadowRays})
    EXPECT_EQ(ownerBytes(owner), 0u) << owner << " without indirect light";
  // Back on: the lights and the hierarchy are built again, and the same bytes held.
  EXPECT_EQ(heldAfter(renderer, still), stillBytes);
}

// The shadow sampling keeps k slots per pixel whatever the number of lights (the LGH paper's fixed
// memory footprint): its bytes per pixel are the same at 1K and at 100K input lights.
TEST_F(FrameMemoryTest, ShadowSamplingBytesPerPixelDoNotFollowTheLights) {
  SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  RenderSettings few = settings, many = settings;
  few.inputLights.vpls = 1000;
  many.inputLights.vpls = 100000;
  heldAfter(renderer, few, 1);
  const size_t fewBytes = ownerBytes(passes::kShadowRays);
  const size_t fewLights = ownerBytes(passes::kInputLights);
  heldAfter(renderer, many, 1);
  EXPECT_GT(fewBytes, 0u);
  EXPECT_EQ(ownerBytes(passes::kShadowRays), fewBytes);
  EXPECT_GT(ownerBytes(passes::kInputLights), 50 * fewLights) << "while S0 grows with the lights";
}

// The hierarchy's memory follows its occupied vertices, never the grid's extent: the same lights in a
// scene 1,000 times larger take the same bytes.
TEST_F(GLTest, HierarchyBytesDoNotFollowTheSceneExtent) {
  LghBuildPass pass(glContext().hasExtension("GL_NV_shader_atomic_float"));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<gpu::GpuLight> lights(20000);
  for (gpu::GpuLight& l : lights) {
    // Lights on a few walls, as VPLs lie: occupied cells are a thin shell of the box.
    glm::vec3 p(u(rng), u(rng), u(rng));
    p[int(3.0f * u(rng)) % 3] = u(rng) < 0.5f ? 0.0f : 1.0f;
    l = gpu::GpuLight{p * 10.0f, 0u, glm::vec3(1.0f), 0u};
  }
  auto hierarchyBytes = [&](float scale) {
    std::vector<gpu::GpuLight> scaled = lights;
    for (gpu::GpuLight& l : scaled) l.position *= scale;
    const gl::Buffer buffer = gl::Buffer::fromVector({"test", "lights"}, scaled);
    GpuHierarchy hierarchy;
    LghBuildOptions options;
    options.eMin = minTopCellFor(17.3 * double(scale));
    pass.execute(buffer, scaled.size(), options, hierarchy);
    EXPECT_GT(hierarchy.grid.levels, 2);
    return ownerBytes(passes::kLghBuild);
  };
  const size_t unit = hierarchyBytes(1.0f), large = hierarchyBytes(1000.0f);
  EXPECT_GT(unit, 0u);
  EXPECT_NEAR(double(large) / double(unit), 1.0, 0.01) << unit << " vs " << large << " bytes";
}

// A level's lookup is sized before its keys are known (S1's from the input lights); what the hierarchy
// keeps is fitted to its occupied vertices: about 2 slots each, whatever the number of lights in them.
TEST_F(GLTest, HierarchyLookupsFollowTheOccupiedVerticesNotTheLights) {
  LghBuildPass pass(glContext().hasExtension("GL_NV_shader_atomic_float"));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // 200,000 lights on 300 spots: many lights per occupied vertex.
  std::vector<gpu::GpuLight> lights(200000);
  for (size_t i = 0; i < lights.size(); ++i) {
    std::mt19937 spot(std::uint32_t(i % 300));
    std::uniform_real_distribution<float> v(0.0f, 10.0f);
    lights[i] =
        gpu::GpuLight{glm::vec3(v(spot), v(spot), v(spot)) + 1e-3f * glm::vec3(u(rng)), 0u, glm::vec3(1.0f), 0u};
  }
  const gl::Buffer buffer = gl::Buffer::fromVector({"test", "lights"}, lights);
  GpuHierarchy hierarchy;
  LghBuildOptions options;
  options.levels = 6;
  options.eMin = minTopCellFor(17.3);
  pass.execute(buffer, lights.size(), options, hierarchy);
  size_t slots = 0;
  for (int level = 1; level <= hierarchy.grid.levels; ++level) {
    const LghLevelLookup& lookup = hierarchy.lookups[size_t(level)];
    const size_t count = hierarchy.levels[size_t(level)].count;
    EXPECT_LE(lookup.capacity, std::max<size_t>(1024, 4 * count)) << "level " << level << ", " << count << " vertices";
    EXPECT_EQ(lookup.keys.size(), lookup.capacity * sizeof(GLuint));
    slots += lookup.capacity;
    // Still a lookup of this level: every occupied slot names a different grid light of it.
    const std::vector<GLuint> keys = lookup.keys.downloadAll<GLuint>(), index = lookup.slotIndex.downloadAll<GLuint>();
    std::vector<bool> named(count, false);
    size_t occupied = 0;
    for (size_t slot = 0; slot < keys.size(); ++slot) {
      if (keys[slot] == gpu::kEmptyKey) continue;
      ++occupied;
      ASSERT_LT(index[slot], count) << "level " << level << " slot " << slot;
      EXPECT_FALSE(named[index[slot]]) << "level " << level << ": grid light " << index[slot] << " named twice";
      named[index[slot]] = true;
    }
    EXPECT_EQ(occupied, count) << "level " << level;
  }
  // The grid lights and their lookups, nothing that follows the 200,000 lights.
  EXPECT_EQ(ownerBytes(passes::kLghBuild), hierarchy.gridLightCount * sizeof(gpu::GpuGridLight) + 2 * slots * 4);
}

TEST_F(FrameMemoryTest, AConfigurationPastTheLimitIsRefusedNamingTheSetting) {
  SceneGpu gpu(scene);
  size_t held = 0;
  {
    Renderer renderer(gpu, settings);
    renderer.render(view());
    held = memory().liveBytes();
  }
  RenderSettings tooMany = settings;
  tooMany.gpuMemoryLimit = float(double(held) / 1e6 + 1.0);  // 1 MB to spare over 4,000 VPLs' frame
  tooMany.inputLights.vpls = 1000000;                        // S0 alone takes 32 MB
  try {
    Renderer renderer(gpu, tooMany);
    renderer.render(view());
    ADD_FAILURE() << "a million VPLs fit in 1 MB";
  } catch (const gl::OutOfMemory& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("input lights: S0"), std::string::npos) << message;
    EXPECT_NE(message.find("vpls"), std::string::npos) << message;
    EXPECT_NE(message.find("gpu-memory-limit"), std::string::npos) << message;
  }
  memory().setLimit(0);
}

}  // namespace
}  // namespace lgh::test
