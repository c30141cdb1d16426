// lgh-viewer as CI runs it: under Xvfb a scripted session renders frames, changes a setting and
// takes screenshots, which must match lgh-render's images of the same settings; without a display
// or without OpenGL 4.5 it must say why and exit non-zero. Skips when lgh-viewer is not built
// (LGH_BUILD_VIEWER=OFF, no Dear ImGui) or, for the Xvfb tests, when xvfb-run is not installed.
#include <OpenImageIO/imageio.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/quaternion.hpp>
#include <iostream>

#include "gl_test_env.h"
#include "gltf_writer.h"

namespace lgh::test {
namespace {

#ifdef LGH_VIEWER_EXE
constexpr const char* kViewer = LGH_VIEWER_EXE;
#else
constexpr const char* kViewer = nullptr;
#endif

#define LGH_REQUIRE_VIEWER() \
  if (!kViewer) GTEST_SKIP() << "lgh-viewer is not built (LGH_BUILD_VIEWER=OFF or Dear ImGui missing)"
#define LGH_REQUIRE_XVFB()                                      \
  LGH_REQUIRE_VIEWER();                                         \
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) \
  GTEST_SKIP() << "xvfb-run is not installed (Debian: apt-get install xvfb xauth)"

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

RunResult runShell(const std::string& command) {
  RunResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string shellQuoted(const std::string& s) { return "'" + s + "'"; }
std::string shellQuoted(const std::filesystem::path& p) { return shellQuoted(p.string()); }

// A virtual display just for this run (-a: a free server number, so tests may run in parallel). The
// X authority file lives in the test's folder: xvfb-run then has no temporary folder of its own to
// delete, a step that once failed here and made it exit before stopping its Xvfb.
std::string underXvfb(const TempDir& dir, const std::string& command) {
  return "xvfb-run -a -f " + shellQuoted(dir / "Xauthority") + " -s '-screen 0 1280x1024x24' " + command;
}

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> values;  // 8-bit values as read, in [0, 1]
};

Image readImage(const std::filesystem::path& file) {
  Image image;
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return image;
  const OIIO::ImageSpec& spec = in->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.values.resize(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data());
  return image;
}

struct Difference {
  double mean = 0, largest = 0;  // of |a - b| over every channel of every pixel, in [0, 1]
};

Difference compare(const Image& a, const Image& b) {
  Difference d;
  if (a.values.size() != b.values.size() || a.values.empty()) return {1.0, 1.0};
  for (size_t i = 0; i < a.values.size(); ++i) {
    const double e = std::abs(double(a.values[i]) - double(b.values[i]));
    d.mean += e;
    d.largest = std::max(d.largest, e);
  }
  d.mean /= double(a.values.size());
  return d;
}

class ViewerTest : public ::testing::Test {
 protected:
  TempDir dir;
  // lgh-viewer with these arguments playing `script`, under Xvfb.
  RunResult runViewerScript(const std::string& arguments, const std::string& script) const {
    return runShell(underXvfb(dir, std::string(kViewer) + " " + arguments + " --script " + shellQuoted(script)));
  }
};

TEST_F(ViewerTest, ScriptedScreenshotsMatchLghRender) {
  LGH_REQUIRE_XVFB();
  // Small and few VPLs: the whole test takes a few seconds. The viewer plays frames at the default
  // alpha first, so the screenshots also show that a changed setting reaches the renderer.
  const std::string common = "--width 160 --height 90 --vpls 2000";
  const std::string script = "frames=2;set alpha=2;frames=1;screenshot=" + (dir / "shadowed.png").string() +
                             ";set shadow-samples=0;frames=1;screenshot=" + (dir / "unshadowed.png").string() +
                             ";view=direct;screenshot=" + (dir / "direct.png").string() + ";quit";
  const RunResult viewer = runViewerScript(common + " -q", script);
  ASSERT_EQ(viewer.exitCode, 0) << viewer.output;

  const std::string render = std::string(LGH_RENDER_EXE) + " " + common + " --alpha 2 -q ";
  // The viewer's screenshot is its third frame: lgh-render's third frame, not accumulated, has the same
  // shadow samples (seeded per frame) and the same single-frame estimate.
  RunResult r = runShell(render + "--frames 3 --accumulate=false -o " + shellQuoted(dir / "render_shadowed.png") +
                         " --aov direct=" + shellQuoted(dir / "render_direct.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runShell(render + "--shadow-samples 0 -o " + shellQuoted(dir / "render_unshadowed.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;

  // The same computation in both programs (with shadows, the same frame's samples): only the display
  // mapping (the viewer's fragment shader, lgh-render's CPU) can round an 8-bit value differently.
  for (const char* name : {"shadowed", "unshadowed", "direct"}) {
    const Image screenshot = readImage(dir / (std::string(name) + ".png"));
    ASSERT_EQ(screenshot.width, 160) << name;
    ASSERT_EQ(screenshot.height, 90) << name;
    const Difference d = compare(screenshot, readImage(dir / ("render_" + std::string(name) + ".png")));
    std::cout << "[ viewer   ] " << name << ": mean |difference| " << d.mean * 255 << "/255, largest "
              << d.largest * 255 << "/255\n";
    EXPECT_LE(d.largest, 1.0 / 255.0 + 1e-6) << name;
  }
}

TEST_F(ViewerTest, SunFromTheCommandLineIsAnEditableLightAndMatchesLghRender) {
  LGH_REQUIRE_XVFB();
  // A scene without lights, --sun 30,45: the viewer's first frame is lgh-render's --sun 30,45; turned
  // through the light panel's path (script light=0 direction=...) to azimuth 120, elevation 60, it is
  // lgh-render's --sun 120,60. Unshadowed indirect light, so the frames are the same computation.
  GltfWriter w;
  const int white = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.8f, 0.8f, 1}));
  const int red = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.1f, 0.1f, 1}));
  w.addNode(NodeDesc{}.withMesh(
      w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, white), quad({-2, 0, -2}, {4, 0, 0}, {0, 2, 0}, red),
                 box({0.3f, 0.4f, 0.0f}, {0.4f, 0.4f, 0.4f}, white)})));
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("eye")))
                .translated({0, 1.6, 4})
                .rotated(glm::angleAxis(glm::radians(-20.0f), glm::vec3(1, 0, 0))));
  const std::filesystem::path scene = w.write(dir / "unlit.gltf");
  const std::string common = shellQuoted(scene) + " --width 160 --height 90 --vpls 2000 --shadow-samples 0 -q";
  // Travel direction of a sun at azimuth 120, elevation 60: -(cos 60 sin 120, sin 60, cos 60 cos 120).
  const std::string script =
      "frames=1;screenshot=" + (dir / "sun.png").string() +
      ";light=0 direction=-0.4330127019,-0.8660254038,0.25;frames=1;screenshot=" + (dir / "turned.png").string() +
      ";quit";
  const RunResult viewer = runViewerScript(common + " --sun 30,45", script);
  ASSERT_EQ(viewer.exitCode, 0) << viewer.output;
  const std::string render = std::string(LGH_RENDER_EXE) + " " + common;
  ASSERT_EQ(runShell(render + " --sun 30,45 -o " + shellQuoted(dir / "render_sun.png")).exitCode, 0);
  ASSERT_EQ(runShell(render + " --sun 120,60 -o " + shellQuoted(dir / "render_turned.png")).exitCode, 0);
  const Image sun = readImage(dir / "sun.png"), turned = readImage(dir / "turned.png");
  const Difference first = compare(sun, readImage(dir / "render_sun.png"));
  const Difference second = compare(turned, readImage(dir / "render_turned.png"));
  std::cout << "[ viewer   ] --sun: largest |difference| " << first.largest * 255
            << "/255; turned in the panel: " << second.largest * 255 << "/255\n";
  EXPECT_LE(first.largest, 1.0 / 255.0 + 1e-6);
  EXPECT_LE(second.largest, 2.0 / 255.0 + 1e-6);  // the direction typed to 10 digits
  EXPECT_GT(compare(sun, turned).mean, 2.0 / 255.0) << "turning the sun changed nothing";
}

// The viewer plays the scene's animation: scripted to time=1 it shows what lgh-render --time 1 renders (the
// lamp and the panel of data/cornell_moving_light.gltf moved there, the BVH and the VPLs with them), and its
// history view shows the frames each pixel holds.
TEST_F(ViewerTest, AnimationTimeMatchesLghRenderAtThatTime) {
  LGH_REQUIRE_VIEWER();
  const std::string scene = shellQuoted(sourceDir() / "data" / "cornell_moving_light.gltf");
  const std::string common = scene + " --width 160 --height 90 --vpls 2000 --shadow-samples 0 -q";
  const std::string script = "time=1;frames=1;screenshot=" + (dir / "at1.png").string() +
                             ";time=0;frames=1;screenshot=" + (dir / "at0.png").string() +
                             ";view=history;frames=2;screenshot=" + (dir / "history.png").string() + ";quit";
  const RunResult viewer = runViewerScript(common, script);
  ASSERT_EQ(viewer.exitCode, 0) << viewer.output;
  ASSERT_EQ(runShell(std::string(LGH_RENDER_EXE) + " " + common + " --time 1 -o " + shellQuoted(dir / "render1.png"))
                .exitCode,
            0);
  const Image at1 = readImage(dir / "at1.png"), at0 = readImage(dir / "at0.png");
  const Difference same = compare(at1, readImage(dir / "render1.png"));
  std::cout << "[ viewer   ] time=1 against lgh-render --time 1: largest |difference| " << same.largest * 255
            << "/255\n";
  EXPECT_LE(same.largest, 1.0 / 255.0 + 1e-6);
  EXPECT_GT(compare(at1, at0).mean, 1.0 / 255.0) << "the animation moved nothing";
  EXPECT_GT(compare(readImage(dir / "history.png"), at0).mean, 1.0 / 255.0) << "the history view shows the image";
}

TEST_F(ViewerTest, WithoutDisplaySaysWhatToDo) {
  LGH_REQUIRE_VIEWER();
  const RunResult r = runShell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(kViewer));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("display"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("xvfb-run"), std::string::npos) << r.output;
}

TEST_F(ViewerTest, BadScriptFailsBeforeTheWindowOpens) {
  LGH_REQUIRE_VIEWER();
  // No display: a mistake in the script must be reported first, not a missing display.
  const RunResult r =
      runShell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(kViewer) + " --script 'frames=1;set alfa=2;quit'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("alfa"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("alpha"), std::string::npos) << "the known names should be listed:\n" << r.output;
}

TEST_F(ViewerTest, WithoutOpenGL45SaysSo) {
  LGH_REQUIRE_XVFB();
  // Mesa caps the version it offers: the window's 4.5 core context cannot be created.
  const RunResult r = runShell(underXvfb(dir, "env MESA_GL_VERSION_OVERRIDE=3.3 " + std::string(kViewer)));
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.exitCode, -1) << "crashed:\n" << r.output;
  EXPECT_NE(r.output.find("OpenGL 4.5"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lgh::test
