// Animation sampling (render/scene/animation.h) against values computed by hand from the glTF 2.0
// specification's interpolation equations (Appendix C), and the posing of a flattened scene.
#include "render/scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/scene/scene.h"

namespace lgh {
namespace {

constexpr double kPi = 3.14159265358979323846;

AnimationChannel channel(AnimationPath path, Interpolation interpolation, std::vector<float> times,
                         std::vector<glm::vec4> keys) {
  AnimationChannel c;
  c.node = 0;
  c.path = path;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.keys = std::move(keys);
  return c;
}

// A rotation of `degrees` about the unit `axis`, as glTF stores it (x, y, z, w).
glm::vec4 rotationKey(double degrees, const glm::dvec3& axis) {
  const double half = 0.5 * degrees * kPi / 180.0;
  return glm::vec4(glm::vec3(axis * std::sin(half)), float(std::cos(half)));
}

void expectNear(const glm::vec4& actual, const glm::vec4& expected, float tolerance = 1e-6f) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

TEST(AnimationSampling, LinearInterpolatesAndHoldsItsEnds) {
  const AnimationChannel c =
      channel(AnimationPath::Translation, Interpolation::Linear, {1.0f, 3.0f}, {{0, 0, 0, 0}, {2, 4, -6, 0}});
  expectNear(sampleChannel(c, 2.0), {1, 2, -3, 0});
  expectNear(sampleChannel(c, 1.5), {0.5f, 1, -1.5f, 0});
  expectNear(sampleChannel(c, 1.0), {0, 0, 0, 0});
  expectNear(sampleChannel(c, 3.0), {2, 4, -6, 0});
  expectNear(sampleChannel(c, -4.0), {0, 0, 0, 0});  // before the first key: the first value
  expectNear(sampleChannel(c, 9.0), {2, 4, -6, 0});  // after the last: the last
}

TEST(AnimationSampling, StepHoldsEachKeyUntilTheNext) {
  const AnimationChannel c = channel(AnimationPath::Scale, Interpolation::Step, {0.0f, 1.0f, 2.0f},
                                     {{1, 1, 1, 0}, {2, 2, 2, 0}, {3, 3, 3, 0}});
  expectNear(sampleChannel(c, 0.999), {1, 1, 1, 0});
  expectNear(sampleChannel(c, 1.0), {2, 2, 2, 0});
  expectNear(sampleChannel(c, 1.5), {2, 2, 2, 0});
  expectNear(sampleChannel(c, 2.0), {3, 3, 3, 0});
  expectNear(sampleChannel(c, 7.0), {3, 3, 3, 0});
}

TEST(AnimationSampling, RotationsSlerpAlongTheShorterArc) {
  const glm::dvec3 y(0, 1, 0);
  const AnimationChannel c =
      channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f}, {rotationKey(0, y), rotationKey(90, y)});
  // Slerp turns at a constant rate: a quarter of the way is 22.5 degrees (linear interpolation of the
  // quaternions, then normalised, would give 20.6).
  expectNear(sampleChannel(c, 0.25), rotationKey(22.5, y));
  expectNear(sampleChannel(c, 0.5), rotationKey(45, y));
  // -q is the same rotation as q: the interpolation must not go the long way round (315 degrees).
  const AnimationChannel flipped =
      channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f}, {rotationKey(0, y), -rotationKey(90, y)});
  const glm::vec4 half = sampleChannel(flipped, 0.5);
  const float sign = half.w < 0 ? -1.0f : 1.0f;
  expectNear(sign * half, rotationKey(45, y));
  // Stored keys that are not quite unit (exporters round) come out unit.
  const AnimationChannel scaled = channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f},
                                          {2.0f * rotationKey(0, y), 0.5f * rotationKey(90, y)});
  expectNear(sampleChannel(scaled, 0.5), rotationKey(45, y));
  expectNear(sampleChannel(scaled, 0.0), rotationKey(0, y));
}

TEST(AnimationSampling, CubicSplineFollowsTheHermiteCurveWithScaledTangents) {
  // Keys (in-tangent, value, out-tangent): v0 = 1 with out-tangent 1 at t = 0; v1 = 3 with in-tangent -1 at
  // t = 2. At u = 1/2: h00 = 1/2, h10 = 1/8, h01 = 1/2, h11 = -1/8, and the tangents scale by the span 2:
  // 0.5 x 1 + 2 x 0.125 x 1 + 0.5 x 3 + 2 x (-0.125) x (-1) = 2.5.
  const AnimationChannel c =
      channel(AnimationPath::Translation, Interpolation::CubicSpline, {0.0f, 2.0f},
              {{9, 9, 9, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {-1, 0, 0, 0}, {3, 0, 0, 0}, {9, 9, 9, 0}});
  EXPECT_NEAR(sampleChannel(c, 1.0).x, 2.5f, 1e-6f);
  // At u = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64: 27/32 + 2 x 9/64 + 15/32 + 2 x 3/64 = 1.6875.
  EXPECT_NEAR(sampleChannel(c, 0.5).x, 1.6875f, 1e-6f);
  // The ends are the values, whatever the outer tangents (9) say.
  expectNear(sampleChannel(c, 0.0), {1, 0, 0, 0});
  expectNear(sampleChannel(c, 2.0), {3, 0, 0, 0});
  expectNear(sampleChannel(c, -1.0), {1, 0, 0, 0});
  expectNear(sampleChannel(c, 5.0), {3, 0, 0, 0});
  // A cubic-spline rotation is normalised: with zero tangents between a rotation and itself scaled by 3,
  // the curve only changes the length.
  const glm::vec4 q = rotationKey(30, glm::dvec3(1, 0, 0));
  const AnimationChannel r = channel(AnimationPath::Rotation, Interpolation::CubicSpline, {0.0f, 1.0f},
                                     {glm::vec4(0), q, glm::vec4(0), glm::vec4(0), 3.0f * q, glm::vec4(0)});
  expectNear(sampleChannel(r, 0.3), q);
}

TEST(AnimationSampling, ChildrenFollowTheirAnimatedParents) {
  SceneAnimation a;
  a.nodes.resize(2);
  a.nodes[0].translation = {1, 0, 0};
  a.nodes[1].parent = 0;
  a.nodes[1].translation = {0, 0, 1};
  a.channels.push_back(channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f},
                               {rotationKey(0, {0, 1, 0}), rotationKey(90, {0, 1, 0})}));
  // Parent rotated 90 degrees about +Y at t = 1: the child's (0, 0, 1) offset becomes (1, 0, 0).
  const glm::dvec3 child(a.worldTransforms(1.0)[1][3]);
  EXPECT_NEAR(child.x, 2.0, 1e-6);
  EXPECT_NEAR(child.y, 0.0, 1e-6);
  EXPECT_NEAR(child.z, 0.0, 1e-6);
  const glm::dvec3 rest(a.worldTransforms(0.0)[1][3]);
  EXPECT_NEAR(rest.x, 1.0, 1e-6);
  EXPECT_NEAR(rest.z, 1.0, 1e-6);
}

TEST(AnimationSampling, PosingMovesVerticesNormalsLightsAndCameras) {
  Scene scene;
  scene.origin = glm::dvec3(10, 0, 0);  // scene space = world - origin
  SceneAnimation& a = scene.animation;
  a.nodes.resize(1);
  a.nodes[0].moves = true;
  a.channels.push_back(channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f},
                               {rotationKey(0, {0, 0, 1}), rotationKey(90, {0, 0, 1})}));
  a.channels.push_back(
      channel(AnimationPath::Translation, Interpolation::Linear, {0.0f, 1.0f}, {{10, 0, 0, 0}, {10, 2, 0, 0}}));
  // A flat-shaded triangle in the xz plane (normal +y, 3 vertices) and a smooth vertex with normal +x.
  MovingPrimitive flat;
  flat.node = 0;
  flat.firstVertex = 0;
  flat.vertexCount = 3;
  flat.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  MovingPrimitive smooth;
  smooth.node = 0;
  smooth.firstVertex = 3;
  smooth.vertexCount = 1;
  smooth.positions = {{1, 0, 0}};
  smooth.normals = {{1, 0, 0}};
  a.primitives = {flat, smooth};
  scene.positions.assign(4, glm::vec3(0));
  scene.normals.assign(4, glm::vec3(0));
  scene.lights.resize(1);
  scene.cameras.resize(1);
  a.lightNodes = {0};
  a.cameraNodes = {0};

  const PoseChange change = poseScene(scene, 1.0);
  EXPECT_TRUE(change.geometry);
  EXPECT_EQ(change.lights, std::vector<size_t>{0});
  EXPECT_TRUE(change.cameras);
  // 90 degrees about +Z maps x -> y and y -> -x; then (10, 2, 0) in world, (0, 2, 0) in scene space.
  const auto expect3 = [](const glm::vec3& actual, const glm::vec3& expected) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-6f) << "component " << i;
  };
  expect3(scene.positions[2], {0, 3, 0});
  expect3(scene.positions[3], {0, 3, 0});
  for (int v = 0; v < 3; ++v) expect3(scene.normals[size_t(v)], {-1, 0, 0});
  expect3(scene.normals[3], {0, 1, 0});
  expect3(scene.lights[0].position, {0, 2, 0});
  expect3(scene.lights[0].direction, {0, 0, -1});  // -Z is the rotation's axis: unchanged
  expect3(scene.cameras[0].position, {0, 2, 0});
  expect3(scene.cameras[0].orientation[0], {0, 1, 0});   // right: x rotated
  expect3(scene.cameras[0].orientation[1], {-1, 0, 0});  // up: y rotated
  // Posed again at the same time, nothing changes, and nothing says so.
  const PoseChange again = poseScene(scene, 1.0);
  EXPECT_FALSE(again.geometry);
  EXPECT_TRUE(again.lights.empty());
  EXPECT_FALSE(again.cameras);
  // A still scene is left as it is.
  Scene still;
  still.positions = {{1, 2, 3}};
  EXPECT_FALSE(poseScene(still, 1.0).geometry);
  expect3(still.positions[0], {1, 2, 3});
}

}  // namespace
}  // namespace lgh
