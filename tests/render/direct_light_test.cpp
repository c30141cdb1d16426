// Direct light against closed-form answers: a plane lit by one punctual light, checked at every
// pixel the camera sees, and a blocker whose shadow (found by an independent ray/box test in double
// precision) must be exactly black.
#include <glm/gtc/quaternion.hpp>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kAlbedo = 0.5f;
const glm::vec3 kLightPosition(0.3f, 2.0f, -0.2f);

struct PlaneScene {
  std::filesystem::path file;
};

// A 10 x 10 m grey plane at y = 0, a light, an optional box blocker, and a camera looking straight down.
std::filesystem::path writePlaneScene(const TempDir& dir, const LightDesc& light, const glm::quat& lightRotation,
                                      bool blocker) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({kAlbedo, kAlbedo, kAlbedo, 1}));
  std::vector<PrimitiveDesc> prims{quad({-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, grey)};
  if (blocker) prims.push_back(box({0.3f, 1.0f, -0.2f}, {0.25f, 0.05f, 0.25f}, grey));
  w.addNode(NodeDesc{}.withMesh(w.addMesh(prims)));
  w.addNode(NodeDesc{}.withLight(w.addLight(light)).translated(kLightPosition).rotated(lightRotation));
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("top").withYfov(1.2).withClip(0.1, 100)))
                .translated({0, 6, 0})
                .rotated(glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))));
  return w.write(dir / "plane.gltf");
}

struct Rendered {
  ImageRGBA radiance, position;
};

Rendered render(const std::filesystem::path& file, int width = 160, int height = 120) {
  const Scene scene = loadScene(file);
  const SceneGpu gpu(scene);
  RenderSettings settings;
  settings.indirectMethod = IndirectMethod::None;  // direct light alone, against its closed form
  settings.image.width = width;
  settings.image.height = height;
  Renderer renderer(gpu, settings);
  const FrameStats stats = renderer.render(makeCameraView(resolveCamera(scene, settings), width, height));
  EXPECT_EQ(stats.nonFinitePixels, 0u);
  return {renderer.readImage(Aov::Final), renderer.readImage(Aov::Position)};
}

// Does the segment from p to the light cross the blocker box (slab test in double)? `margin` > 0
// shrinks the box (robustly blocked), < 0 grows it (robustly clear).
bool segmentHitsBox(const glm::dvec3& p, const glm::dvec3& light, double margin) {
  const glm::dvec3 lo = glm::dvec3(0.05, 0.95, -0.45) + margin, hi = glm::dvec3(0.55, 1.05, 0.05) - margin;
  const glm::dvec3 d = light - p;
  double t0 = 0.0, t1 = 1.0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      if (p[a] < lo[a] || p[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - p[a]) / d[a], tb = (hi[a] - p[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

class DirectLightTest : public GLTest {
 protected:
  TempDir dir;
};

// L = rho/pi * I * cos(theta) / d^2 for a point light.
TEST_F(DirectLightTest, PointLightOverPlaneMatchesClosedForm) {
  const double intensity = 12.0;
  const Rendered r = render(writePlaneScene(dir, LightDesc{}.withIntensity(intensity), glm::quat(1, 0, 0, 0), false));
  size_t checked = 0;
  double worst = 0;
  for (int y = 0; y < r.position.height; ++y)
    for (int x = 0; x < r.position.width; ++x) {
      const glm::vec4 p = r.position.at(x, y);
      if (p.w == 0) continue;
      const glm::dvec3 toLight = glm::dvec3(kLightPosition) - glm::dvec3(p);
      const double d2 = glm::dot(toLight, toLight), cosTheta = toLight.y / std::sqrt(d2);
      const double expected = kAlbedo / kPi * intensity * cosTheta / d2;
      const double actual = r.radiance.at(x, y).g;
      worst = std::max(worst, std::abs(actual - expected) / expected);
      ASSERT_NEAR(actual, expected, 0.01 * expected) << "pixel " << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 1000u);
  RecordProperty("worstRelativeError", std::to_string(worst));
}

// A spot light pointing straight down with glTF's cone falloff: full intensity inside the inner cone,
// (linear ramp in cos)^2 between the cones, nothing outside.
TEST_F(DirectLightTest, SpotLightConeFollowsGltfFalloff) {
  const double intensity = 30.0, inner = 0.3, outer = 0.6;
  const glm::quat down = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));  // local -Z to world -Y
  const Rendered r = render(
      writePlaneScene(dir, LightDesc{}.ofType("spot").withIntensity(intensity).withCone(inner, outer), down, false));
  size_t inside = 0, ramp = 0, outside = 0;
  for (int y = 0; y < r.position.height; ++y)
    for (int x = 0; x < r.position.width; ++x) {
      const glm::vec4 p = r.position.at(x, y);
      if (p.w == 0) continue;
      const glm::dvec3 toLight = glm::dvec3(kLightPosition) - glm::dvec3(p);
      const double d = glm::length(toLight), cd = toLight.y / d;  // cos to the spot axis (straight down)
      const double t = std::clamp((cd - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
      const double expected = kAlbedo / kPi * intensity * t * t * cd / (d * d);
      const double actual = r.radiance.at(x, y).g;
      if (t == 0.0) {
        ++outside;
        ASSERT_EQ(actual, 0.0f);
      } else {
        ++(t == 1.0 ? inside : ramp);
        ASSERT_NEAR(actual, expected, 0.01 * expected + 1e-6) << "pixel " << x << "," << y;
      }
    }
  EXPECT_GT(inside, 100u);
  EXPECT_GT(ramp, 100u);
  EXPECT_GT(outside, 100u);
}

TEST_F(DirectLightTest, DirectionalLightGivesCosineIrradiance) {
  const double lux = 3.0;
  // Travelling down and sideways: 30 degrees from the vertical.
  const glm::quat tilt = glm::angleAxis(glm::radians(-60.0f), glm::vec3(1, 0, 0));
  const Rendered r = render(writePlaneScene(dir, LightDesc{}.ofType("directional").withIntensity(lux), tilt, false));
  const double expected = kAlbedo / kPi * lux * std::cos(glm::radians(30.0));
  size_t checked = 0;
  for (int y = 0; y < r.position.height; ++y)
    for (int x = 0; x < r.position.width; ++x) {
      if (r.position.at(x, y).w == 0) continue;
      ASSERT_NEAR(r.radiance.at(x, y).g, expected, 0.01 * expected);
      ++checked;
    }
  EXPECT_GT(checked, 1000u);
}

// A blocker between the light and the plane: pixels whose segment to the light crosses it (with a
// margin against rounding at the shadow's edge) are exactly 0; pixels robustly clear of it still
// match the closed form.
TEST_F(DirectLightTest, BlockerCastsExactlyBlackShadow) {
  const double intensity = 12.0;
  const Rendered r = render(writePlaneScene(dir, LightDesc{}.withIntensity(intensity), glm::quat(1, 0, 0, 0), true));
  size_t shadowed = 0, lit = 0;
  for (int y = 0; y < r.position.height; ++y)
    for (int x = 0; x < r.position.width; ++x) {
      const glm::vec4 p = r.position.at(x, y);
      if (p.w == 0 || p.y > 0.5f) continue;  // the plane only, not the blocker itself
      const glm::dvec3 pos(p);
      const double actual = r.radiance.at(x, y).g;
      if (segmentHitsBox(pos, glm::dvec3(kLightPosition), 0.01)) {
        ASSERT_EQ(actual, 0.0) << "pixel " << x << "," << y << " should be in shadow";
        ++shadowed;
      } else if (!segmentHitsBox(pos, glm::dvec3(kLightPosition), -0.01)) {
        const glm::dvec3 toLight = glm::dvec3(kLightPosition) - pos;
        const double d2 = glm::dot(toLight, toLight);
        const double expected = kAlbedo / kPi * intensity * (toLight.y / std::sqrt(d2)) / d2;
        ASSERT_NEAR(actual, expected, 0.01 * expected) << "pixel " << x << "," << y << " should be lit";
        ++lit;
      }
    }
  EXPECT_GT(shadowed, 100u);
  EXPECT_GT(lit, 1000u);
}

}  // namespace
}  // namespace lgh::test
