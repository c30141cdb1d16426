// Strict glTF 2.0 (render/scene/gltf_loader.cpp): every file of malformed_gltf.h is rejected with a
// SceneLoadError whose message starts with the file's path and names the problem, never a crash.
// No GL: this file is also built with AddressSanitizer + UBSan into scene_sanitize_tests
// (tests/CMakeLists.txt), which runs in the normal suite.
#include <gtest/gtest.h>

#include "gltf_writer.h"
#include "malformed_gltf.h"
#include "render/scene/scene.h"

namespace lgh::test {
namespace {

class MalformedGltfTest : public ::testing::TestWithParam<MalformedGltf> {};

TEST_P(MalformedGltfTest, IsRejectedNamingFileAndProblem) {
  const MalformedGltf& c = GetParam();
  TempDir dir;
  const std::filesystem::path file = c.write(dir.path());
  SCOPED_TRACE(c.rule);
  try {
    const Scene scene = loadScene(file);
    ADD_FAILURE() << "loaded " << scene.triangleCount() << " triangles from a file that breaks " << c.rule;
  } catch (const SceneLoadError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << "does not start with the path: " << message;
    for (const std::string& word : c.expectedWords)
      EXPECT_NE(message.find(word), std::string::npos) << "no '" << word << "' in: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(Strict, MalformedGltfTest, ::testing::ValuesIn(malformedGltfCases()),
                         [](const ::testing::TestParamInfo<MalformedGltf>& info) { return info.param.name; });

// The base scene the malformed files start from is itself valid: each failure above is the one edit.
TEST(MalformedGltfBase, UnbrokenSceneLoads) {
  TempDir dir;
  const Scene scene = loadScene(writeUnbrokenGltf(dir.path()));
  EXPECT_EQ(scene.triangleCount(), 2u);
  EXPECT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.cameras.size(), 1u);
  EXPECT_GE(malformedGltfCases().size(), 10u);
}

TEST(MalformedGltfBase, UnbrokenAnimatedSceneLoadsAndPlays) {
  TempDir dir;
  Scene scene = loadScene(writeUnbrokenAnimatedGltf(dir.path()));
  ASSERT_EQ(scene.animation.channels.size(), 1u);
  EXPECT_EQ(scene.animation.start, 0.0);
  EXPECT_EQ(scene.animation.end, 1.0);
  EXPECT_TRUE(scene.animation.primitives.empty());  // the floor does not move: no copy of it is kept
  const PoseChange change = poseScene(scene, 0.25);
  EXPECT_FALSE(change.geometry);
  ASSERT_EQ(change.lights, std::vector<size_t>{0});
  EXPECT_FLOAT_EQ(scene.lights[0].position.x, 0.25f);
  EXPECT_FLOAT_EQ(scene.lights[0].position.y, 2.0f);
}

}  // namespace
}  // namespace lgh::test
