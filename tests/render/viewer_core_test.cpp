// The viewer's parts that need no window: the script parser and the camera controller.
#ifdef LGH_VIEWER_CORE
#include <gtest/gtest.h>

#include <cmath>

#include "render/app/viewer_camera.h"
#include "render/app/viewer_script.h"

namespace lgh::test {
namespace {

using Kind = ScriptCommand::Kind;

TEST(ViewerScript, ParsesEveryCommand) {
  const std::vector<ScriptCommand> c = parseScript(
      " frames=3; set alpha=2 ;view=overdraw;points=2;light=0 direction=0,-1,0.5;window=320x200;"
      "screenshot=a.png;window-screenshot=b.png;quit;");
  ASSERT_EQ(c.size(), 9u);
  EXPECT_EQ(c[0].kind, Kind::Frames);
  EXPECT_EQ(c[0].number, 3);
  EXPECT_EQ(c[1].kind, Kind::Set);
  EXPECT_EQ(c[1].name, "alpha");
  EXPECT_EQ(c[1].value, "2");
  EXPECT_EQ(c[2].kind, Kind::View);
  EXPECT_EQ(c[2].name, "overdraw");
  EXPECT_EQ(c[3].kind, Kind::Points);
  EXPECT_EQ(c[3].number, 2);
  EXPECT_EQ(c[4].kind, Kind::Light);
  EXPECT_EQ(c[4].name, "direction");
  EXPECT_EQ(c[4].vector, glm::vec3(0, -1, 0.5f));
  EXPECT_EQ(c[5].kind, Kind::WindowSize);
  EXPECT_EQ(c[5].size, glm::ivec2(320, 200));
  EXPECT_EQ(c[6].kind, Kind::Screenshot);
  EXPECT_EQ(c[6].name, "a.png");
  EXPECT_EQ(c[7].kind, Kind::WindowScreenshot);
  EXPECT_EQ(c[8].kind, Kind::Quit);
  EXPECT_TRUE(parseScript("").empty());
}

TEST(ViewerScript, MistakesNameTheCommand) {
  for (const char* bad :
       {"frames=0", "frames=two", "set alpha", "set alfa=2", "set alpha=100", "set vpls=1e3", "view=shadows",
        "points=-1", "light=0 position=1,2", "light=0 colour=1,1,1", "light=0 direction=0,0,0", "screenshot=a.gif",
        "window-screenshot=a.exr", "window=0x10", "quit now", "render"}) {
    SCOPED_TRACE(bad);
    try {
      parseScript(std::string("frames=1;") + bad);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(ViewerScript, SettingsByTheirCliNamesWithinTheirRanges) {
  RenderSettings s;
  setSetting(s, "shadow-skip-finest", "false");
  setSetting(s, "vpls", "5000");
  setSetting(s, "alpha", "2.5");
  setSetting(s, "tonemap", "reinhard");
  EXPECT_FALSE(s.shadows.skipFinest);
  EXPECT_EQ(s.inputLights.vpls, 5000);
  EXPECT_FLOAT_EQ(s.lightPass.alpha, 2.5f);
  EXPECT_EQ(s.image.toneMap, "reinhard");
  try {
    setSetting(s, "alpha", "0.1");
    ADD_FAILURE() << "alpha 0.1 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0.25"), std::string::npos) << "the range should be named: " << e.what();
  }
  EXPECT_THROW(setSetting(s, "indirect-method", "maybe"), std::invalid_argument);
  EXPECT_THROW(setSetting(s, "seed", "99999999999"), std::invalid_argument);
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance) {
  EXPECT_LT(glm::length(a - b), tolerance)
      << a.x << "," << a.y << "," << a.z << " vs " << b.x << "," << b.y << "," << b.z;
}

Camera sceneCamera() {
  Camera c;
  c.position = {1.0f, 2.0f, 5.0f};
  const glm::vec3 forward = glm::normalize(glm::vec3(-0.2f, -0.3f, -1.0f));
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  c.orientation = glm::mat3(right, glm::cross(right, forward), -forward);
  return c;
}

TEST(CameraController, UntouchedIsExactlyTheSceneCamera) {
  CameraController controller;
  controller.reset(sceneCamera(), 10.0f);
  EXPECT_EQ(controller.camera().position, sceneCamera().position);
  EXPECT_EQ(controller.camera().orientation, sceneCamera().orientation);
}

TEST(CameraController, OrbitCirclesTheTargetAndLookKeepsThePosition) {
  CameraController controller;
  controller.reset(sceneCamera(), 9.0f);
  const Camera start = controller.camera();
  const glm::vec3 target = start.position - start.orientation[2] * controller.targetDistance();
  for (int i = 0; i < 8; ++i) {
    controller.orbit(2.0f * 3.14159265f / 8.0f, 0.0f);
    const Camera& c = controller.camera();
    expectNear(c.position - c.orientation[2] * controller.targetDistance(), target, 1e-4f);  // still aimed at it
  }
  expectNear(controller.camera().position, start.position, 1e-4f);  // a full turn comes back
  expectNear(controller.camera().orientation[2], start.orientation[2], 1e-5f);

  controller.look(0.3f, -0.2f);
  expectNear(controller.camera().position, start.position, 1e-4f);
  const glm::mat3 o = controller.camera().orientation;
  EXPECT_NEAR(glm::dot(o[0], glm::vec3(0, 1, 0)), 0.0f, 1e-6f);  // no roll
  EXPECT_NEAR(glm::determinant(o), 1.0f, 1e-5f);                 // right-handed, orthonormal
}

TEST(CameraController, DollyApproachesWithoutPassingAndPanMovesSideways) {
  CameraController controller;
  controller.reset(sceneCamera(), 9.0f);
  const Camera start = controller.camera();
  const float distance = controller.targetDistance();
  controller.dolly(3.0f);
  const glm::vec3 moved = controller.camera().position - start.position;
  EXPECT_NEAR(glm::length(moved) + controller.targetDistance(), distance, 1e-4f);
  EXPECT_GT(glm::dot(moved, -start.orientation[2]), 0.0f);
  controller.dolly(-3.0f);
  expectNear(controller.camera().position, start.position, 1e-4f);

  controller.pan(0.1f, 0.0f);
  expectNear(controller.camera().position - start.position, start.orientation[0] * 0.9f, 1e-4f);
}

}  // namespace
}  // namespace lgh::test
#endif
