// Animated glTF files played on the flattened scene (gltf_animation.cpp, animation.cpp): a scene posed at
// time t must equal the same file made still with each animated node's transform set to the channels'
// values at t, as the loader flattens it. The two share no code for composing transforms (the loader's
// gltf_nodes.cpp against SceneAnimation::worldTransforms), nor for flat normals or mirrored winding.
// Loader only, built into scene_sanitize_tests (AddressSanitizer + UBSan).
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "gltf_writer.h"
#include "render/scene/scene.h"

namespace lgh::test {
namespace {

namespace fs = std::filesystem;

glm::quat about(float degrees, const glm::vec3& axis) { return glm::angleAxis(glm::radians(degrees), axis); }

// An arm (a box, flat normals) turning and sliding, a mirrored child panel with normals scaled on a STEP
// channel, a still floor, and a lamp and a camera riding the arm. With `at` set, every node's transform is
// instead the animation's value at that time and the file has no animation.
fs::path writeRig(const fs::path& file, const SceneAnimation* at = nullptr, double time = 0.0) {
  GltfWriter w;
  PrimitiveDesc panel = quad({-0.5f, 0, -0.5f}, {1, 0, 0}, {0, 0, 1});
  panel.normals.assign(panel.positions.size(), glm::normalize(glm::vec3(0.2f, -1, 0.1f)));
  const int floorMesh = w.addMesh({quad({-5, -1, -5}, {10, 0, 0}, {0, 0, 10})});
  PrimitiveDesc flatBox = box({0, 0, 0}, {1, 0.2f, 0.3f});
  flatBox.normals.clear();  // flat shading: the loader makes face normals
  const int armMesh = w.addMesh({flatBox});
  const int panelMesh = w.addMesh({panel});
  NodeDesc panelNode = NodeDesc{}.named("panel").withMesh(panelMesh).translated({2, 0, 0}).scaled({-1, 1, 2});
  NodeDesc lamp = NodeDesc{}.named("lamp").withLight(w.addLight(LightDesc{}.withIntensity(5))).translated({0, 1, 0});
  NodeDesc eye = NodeDesc{}.named("eye").withCamera(w.addCamera(CameraDesc{})).translated({0, 0.5f, 3});
  NodeDesc arm = NodeDesc{}.named("arm").withMesh(armMesh).withChildren({2, 3, 4}).translated({0, 1, 0});
  if (at) {
    for (const AnimationChannel& c : at->channels) {
      const glm::vec4 v = sampleChannel(c, time);
      NodeDesc& node = c.node == 1 ? arm : panelNode;
      if (c.path == AnimationPath::Translation) node.translation = glm::dvec3(v);
      if (c.path == AnimationPath::Rotation) node.rotation = glm::quat(v.w, v.x, v.y, v.z);
      if (c.path == AnimationPath::Scale) node.scale = glm::vec3(v);
    }
  }
  w.addNode(NodeDesc{}.named("floor").withMesh(floorMesh));  // 0
  w.addNode(arm);                                            // 1
  w.addNode(panelNode);                                      // 2
  w.addNode(lamp);                                           // 3
  w.addNode(eye);                                            // 4
  if (!at) {
    const glm::quat q0 = about(0, {0, 1, 0}), q1 = about(120, {0, 1, 0}), q2 = about(200, {0.6f, 0.8f, 0});
    w.addAnimationChannel(1, "rotation", {0, 1, 2},
                          {q0.x, q0.y, q0.z, q0.w, q1.x, q1.y, q1.z, q1.w, q2.x, q2.y, q2.z, q2.w});
    // CUBICSPLINE: in-tangent, value, out-tangent per key.
    w.addAnimationChannel(1, "translation", {0, 2}, {0, 0, 0, 0, 1, 0, 1, 0, 0, /**/ 0, 2, 0, 1, 1, 0.5f, 0, 0, 0},
                          "CUBICSPLINE");
    w.addAnimationChannel(2, "scale", {0, 0.5f, 1.5f}, {-1, 1, 2, -1, 1, 1, -0.5f, 2, 1}, "STEP");
  }
  return w.write(file);
}

void expectSameVectors(const std::vector<glm::vec3>& posed, const std::vector<glm::vec3>& still, const char* what,
                       float tolerance) {
  ASSERT_EQ(posed.size(), still.size()) << what;
  for (size_t i = 0; i < posed.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(posed[i][c], still[i][c], tolerance) << what << " " << i << " component " << c;
}

TEST(AnimationLoad, PosedSceneEqualsTheStillSceneAtThatTime) {
  TempDir dir;
  Scene animated = loadScene(writeRig(dir / "rig.gltf"));
  ASSERT_EQ(animated.animation.channels.size(), 3u);
  EXPECT_EQ(animated.animation.end, 2.0);
  // The arm (a box: 12 flat triangles) and the panel (2 triangles, 4 vertices with normals) move; the floor not.
  ASSERT_EQ(animated.animation.primitives.size(), 2u);
  EXPECT_EQ(animated.animation.primitives[0].vertexCount, 36u);
  EXPECT_TRUE(animated.animation.primitives[0].normals.empty());
  EXPECT_EQ(animated.animation.primitives[1].vertexCount, 4u);

  for (double time : {0.0, 0.3, 0.5, 1.0, 1.7, 2.0, 3.0}) {
    SCOPED_TRACE("time " + std::to_string(time));
    const Scene still = loadScene(writeRig(dir / "still.gltf", &animated.animation, time));
    poseScene(animated, time);
    expectSameVectors(animated.positions, still.positions, "position", 2e-5f);
    expectSameVectors(animated.normals, still.normals, "normal", 2e-5f);
    ASSERT_EQ(animated.indices, still.indices);  // mirrored winding as the loader sets it
    expectSameVectors({animated.lights[0].position, animated.lights[0].direction},
                      {still.lights[0].position, still.lights[0].direction}, "light", 2e-5f);
    expectSameVectors({animated.cameras[0].position, animated.cameras[0].orientation[0],
                       animated.cameras[0].orientation[1], animated.cameras[0].orientation[2]},
                      {still.cameras[0].position, still.cameras[0].orientation[0], still.cameras[0].orientation[1],
                       still.cameras[0].orientation[2]},
                      "camera", 2e-5f);
    // The animated scene's bounds hold the scene at every time.
    for (const glm::vec3& p : still.positions) {
      EXPECT_TRUE(glm::all(glm::lessThanEqual(animated.bounds.min, p + 1e-5f)));
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(animated.bounds.max, p - 1e-5f)));
    }
  }
}

}  // namespace
}  // namespace lgh::test
