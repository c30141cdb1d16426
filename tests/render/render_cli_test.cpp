// lgh-render as a user runs it: each backend renders the default scene, outputs are valid images,
// and every kind of bad input ends with a non-zero exit and a message naming the problem.
#include <OpenImageIO/imageio.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "malformed_gltf.h"

namespace lgh::test {
namespace {

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// Runs lgh-render with `arguments`; `environment` prefixes the command (e.g. "env -u DISPLAY").
RunResult runRender(const std::string& arguments, const std::string& environment = "") {
  const std::string command = environment + " " + std::string(LGH_RENDER_EXE) + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// Mean of the image's channels, read back through OpenImageIO.
double meanValue(const std::filesystem::path& file, int* width, int* height) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return -1;
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  *width = spec.width;
  *height = spec.height;
  double sum = 0;
  for (float v : pixels) sum += v;
  return sum / double(pixels.size());
}

class RenderCliTest : public ::testing::Test {
 protected:
  TempDir dir;
};

TEST_F(RenderCliTest, EachHeadlessBackendRendersTheDefaultScene) {
  double means[2] = {0, 0};
  int i = 0;
  for (const char* backend : {"egl-surfaceless", "osmesa"}) {
    const auto out = dir / (std::string(backend) + ".exr");
    const RunResult r = runRender("--backend " + std::string(backend) + " --width 96 --height 72 -o " + quoted(out));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("triangles"), std::string::npos) << "summary missing:\n" << r.output;
    for (const char* memory : {"GPU memory", "G-buffer", "LGH build", "peak"})
      EXPECT_NE(r.output.find(memory), std::string::npos) << "memory by owner missing:\n" << r.output;
    int w = 0, h = 0;
    means[i] = meanValue(out, &w, &h);
    EXPECT_EQ(w, 96);
    EXPECT_EQ(h, 72);
    EXPECT_GT(means[i++], 0.01) << backend << " rendered a black image";
  }
  // Same renderer, same software rasterizer: the backends must agree closely.
  EXPECT_NEAR(means[0], means[1], 1e-4 * means[0]);
}

TEST_F(RenderCliTest, PngIsToneMappedAndAovsAreWritten) {
  const auto png = dir / "final.png", direct = dir / "direct.exr";
  const RunResult r = runRender("--width 64 --height 48 -q -o " + quoted(png) + " --aov direct=" + quoted(direct));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(r.output.empty()) << "--quiet printed: " << r.output;
  int w = 0, h = 0;
  const double pngMean = meanValue(png, &w, &h);
  EXPECT_GT(pngMean, 0.0);
  EXPECT_LE(pngMean, 1.0);
  EXPECT_GT(meanValue(direct, &w, &h), 0.0);
}

struct BadInvocation {
  const char* name;
  std::string arguments;
  std::vector<std::string> expectedWords;  // all must appear in the output
};

TEST_F(RenderCliTest, BadInputsFailWithClearMessages) {
  const auto missing = dir / "no_such_scene.gltf";
  const auto badJson = dir / "bad.gltf";
  writeTextFile(badJson, "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ ");
  const auto out = dir / "out.png";
  const std::vector<BadInvocation> cases = {
      {"missing scene", quoted(missing) + " -o " + quoted(out), {"no_such_scene.gltf"}},
      {"bad JSON", quoted(badJson) + " -o " + quoted(out), {"bad.gltf"}},
      {"unknown backend", "--backend vulkan -o " + quoted(out), {"vulkan", "egl", "osmesa"}},
      {"unknown camera", "--camera nowhere -o " + quoted(out), {"nowhere", "front"}},
      {"unsupported output format", "-o " + quoted(dir / "out.gif"), {"out.gif", ".exr"}},
      {"zero width", "--width 0 -o " + quoted(out), {"width"}},
      {"bad AOV", "--aov shadows=x.exr -o " + quoted(out), {"shadows", "direct"}},
      {"unknown option", "--frobnicate -o " + quoted(out), {"frobnicate"}},
      {"past the memory limit",
       "--width 160 --height 90 --gpu-memory-limit 20 --vpls 1000000 -o " + quoted(out),
       {"GPU memory", "input lights: S0", "vpls", "32.0 MB", "gpu-memory-limit"}},
  };
  for (const BadInvocation& c : cases) {
    SCOPED_TRACE(c.name);
    const RunResult r = runRender(c.arguments);
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.exitCode, -1) << "crashed:\n" << r.output;
    for (const std::string& word : c.expectedWords) EXPECT_NE(r.output.find(word), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out)) << "a failed run left an output image";
}

TEST_F(RenderCliTest, MalformedGltfExitsWithStatusOneNamingFileAndProblem) {
  // Every case of malformed_gltf.h through the real binary: exit status exactly 1 (not a crash, not
  // a signal), "lgh-render: error: <file>: <problem>", and no image left behind. The runs start
  // together: each spends ~2 s starting up (shared libraries) and a few ms failing.
  const auto out = dir / "out.png";
  const std::vector<MalformedGltf>& cases = malformedGltfCases();
  std::vector<std::filesystem::path> files;
  std::vector<FILE*> pipes;
  for (const MalformedGltf& c : cases) {
    files.push_back(c.write(dir.path()));
    const std::string command =
        std::string(LGH_RENDER_EXE) + " " + quoted(files.back()) + " -o " + quoted(out) + " 2>&1";
    pipes.push_back(popen(command.c_str(), "r"));
    ASSERT_NE(pipes.back(), nullptr);
  }
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].name + " (" + cases[i].rule + ")");
    std::string output;
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipes[i])) > 0) output.append(buffer.data(), n);
    const int status = pclose(pipes[i]);
    EXPECT_TRUE(WIFEXITED(status)) << "crashed:\n" << output;
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 1) << output;
    EXPECT_NE(output.find("lgh-render: error: " + files[i].string() + ": "), std::string::npos) << output;
    for (const std::string& word : cases[i].expectedWords) EXPECT_NE(output.find(word), std::string::npos) << output;
  }
  EXPECT_FALSE(std::filesystem::exists(out)) << "a failed run left an output image";
}

// A floor, a box and a wall with a camera, no light at all: what most glTF models are.
std::filesystem::path writeUnlitScene(const TempDir& dir, const glm::dvec3& offset = glm::dvec3(0.0)) {
  GltfWriter w;
  const int white = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.8f, 0.8f, 1}));
  const int red = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.1f, 0.1f, 1}));
  const int mesh =
      w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, white), quad({-2, 0, -2}, {4, 0, 0}, {0, 2, 0}, red),
                 box({0.3f, 0.4f, 0.0f}, {0.4f, 0.4f, 0.4f}, white)});
  const int site = w.addNode(NodeDesc{}.withMesh(mesh));
  const int eye = w.addNode(NodeDesc{}
                                .withCamera(w.addCamera(CameraDesc{}.named("eye")))
                                .translated({0, 1.6, 4})
                                .rotated(glm::angleAxis(glm::radians(-20.0f), glm::vec3(1, 0, 0))));
  w.addNode(NodeDesc{}.translated(offset).withChildren({site, eye}));
  return w.write(dir / "unlit.gltf");
}

TEST_F(RenderCliTest, SceneWithoutLightsHintsAtSunAndPointAndStillWritesItsImage) {
  const auto scene = writeUnlitScene(dir);
  const auto dark = dir / "dark.exr";
  const RunResult r = runRender(quoted(scene) + " --width 160 --height 90 --vpls 4000 -o " + quoted(dark));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const size_t hint = r.output.find("no lights");
  ASSERT_NE(hint, std::string::npos) << r.output;
  const std::string line = r.output.substr(hint, r.output.find('\n', hint) - hint);
  EXPECT_NE(line.find("--sun AZIMUTH,ELEVATION[,LUX]"), std::string::npos) << line;
  EXPECT_NE(line.find("--point X,Y,Z,INTENSITY[,R,G,B]"), std::string::npos) << line;
  int w = 0, h = 0;
  EXPECT_EQ(meanValue(dark, &w, &h), 0.0);
  EXPECT_EQ(w, 160);
}

TEST_F(RenderCliTest, SunLightsASceneWithoutLightsWithGlobalIllumination) {
  // lgh-render MODEL.gltf --sun 30,45: direct sunlight plus indirect light through the VPLs.
  const auto scene = writeUnlitScene(dir);
  const auto image = dir / "sun.exr", indirect = dir / "indirect.exr", direct = dir / "direct.exr";
  const RunResult r = runRender(quoted(scene) + " --sun 30,45 --width 160 --height 90 --vpls 4000 -o " + quoted(image) +
                                " --aov indirect=" + quoted(indirect) + " --aov direct=" + quoted(direct));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("no lights"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("VPLs"), std::string::npos) << r.output;
  int w = 0, h = 0;
  const double directMean = meanValue(direct, &w, &h), indirectMean = meanValue(indirect, &w, &h);
  EXPECT_GT(directMean, 0.05);
  EXPECT_GT(indirectMean, 0.01 * directMean) << "no indirect light";
  // Half the lux, half the light (direct and indirect scale with the sun).
  const auto halfImage = dir / "half.exr";
  ASSERT_EQ(
      runRender(quoted(scene) + " --sun 30,45,4 --width 160 --height 90 --vpls 4000 -o " + quoted(halfImage)).exitCode,
      0);
  EXPECT_NEAR(meanValue(halfImage, &w, &h), 0.5 * meanValue(image, &w, &h), 1e-3 * meanValue(image, &w, &h));
}

TEST_F(RenderCliTest, PointTakesWorldCoordinatesOfASceneFarFromTheOrigin) {
  // The same unlit scene at the origin and 1e5 away, each lit by --point at the same spot relative to
  // the scene, in the file's (world) coordinates: the same image.
  TempDir far;
  const auto near = dir / "near.exr", away = dir / "away.exr";
  const std::string size = " --width 160 --height 90 --vpls 4000 --shadow-samples 0";
  ASSERT_EQ(runRender(quoted(writeUnlitScene(dir)) + " --point -0.5,1.5,1,5" + size + " -o " + quoted(near)).exitCode,
            0);
  const RunResult r =
      runRender(quoted(writeUnlitScene(far, {1e5, 0, 0})) + " --point 99999.5,1.5,1,5" + size + " -o " + quoted(away));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  int w = 0, h = 0;
  const double a = meanValue(near, &w, &h), b = meanValue(away, &w, &h);
  EXPECT_GT(a, 0.01);
  EXPECT_NEAR(b, a, 1e-4 * a);
}

TEST_F(RenderCliTest, BadSunAndPointValuesFailWithTheirForm) {
  const auto out = dir / "out.png";
  const std::vector<BadInvocation> cases = {
      {"sun with one number", "--sun 30 -o " + quoted(out), {"--sun", "AZIMUTH,ELEVATION[,LUX]"}},
      {"sun below the nadir", "--sun 30,120 -o " + quoted(out), {"--sun", "elevation", "[-90, 90]"}},
      {"sun not a number", "--sun 30,high -o " + quoted(out), {"--sun", "'high'"}},
      {"point with 5 numbers", "--point 0,1,0,5,1 -o " + quoted(out), {"--point", "R,G,B"}},
      {"point with negative intensity", "--point 0,1,0,-5 -o " + quoted(out), {"--point", "INTENSITY"}},
  };
  for (const BadInvocation& c : cases) {
    SCOPED_TRACE(c.name);
    const RunResult r = runRender(c.arguments);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    for (const std::string& word : c.expectedWords) EXPECT_NE(r.output.find(word), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

// --sequence renders the animation frame by frame to the numbered files of the output pattern: the moving
// lamp of data/cornell_moving_light.gltf changes every frame, and --time 1 renders the frame at 1 s.
TEST_F(RenderCliTest, SequenceWritesNumberedFramesOfTheAnimation) {
  const std::string scene = quoted(sourceDir() / "data" / "cornell_moving_light.gltf");
  const std::string size = " --width 96 --height 54 --vpls 2000 --shadow-samples 0";
  const RunResult r = runRender(scene + size + " --sequence 3 --fps 2 -o " + quoted(dir / "f_%02d.exr"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  int w = 0, h = 0;
  std::vector<double> means;
  for (int f = 0; f < 3; ++f) means.push_back(meanValue(dir / ("f_0" + std::to_string(f) + ".exr"), &w, &h));
  EXPECT_GT(means[0], 0.0);
  EXPECT_NE(means[0], means[1]);
  EXPECT_NE(means[1], means[2]);
  // The frame at 1 s (frame 2 at 2 frames a second) is the still image at --time 1; without %d a pattern
  // gets _NNNN before its extension.
  ASSERT_EQ(runRender(scene + size + " --time 1 -o " + quoted(dir / "at1.exr")).exitCode, 0);
  EXPECT_NEAR(meanValue(dir / "at1.exr", &w, &h), means[2], 1e-6 * means[2]);
  ASSERT_EQ(runRender(scene + size + " --sequence 1 -o " + quoted(dir / "plain.exr")).exitCode, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "plain_0000.exr"));
  // A pattern printf would read more from, and --frames with --sequence, are refused before any work.
  const std::vector<BadInvocation> cases = {
      {"pattern with %s", scene + " --sequence 2 -o " + quoted(dir / "f_%s.png"), {"%d", "nothing else"}},
      {"--frames and --sequence", scene + " --sequence 2 --frames 4 -o " + quoted(dir / "f.png"), {"excludes"}},
      {"bad --sun-step", scene + " --sequence 2 --sun-step 1 -o " + quoted(dir / "f.png"), {"--sun-step", "DAZIMUTH"}},
  };
  for (const BadInvocation& c : cases) {
    SCOPED_TRACE(c.name);
    const RunResult bad = runRender(c.arguments);
    EXPECT_NE(bad.exitCode, 0) << bad.output;
    EXPECT_NE(bad.exitCode, -1) << "crashed:\n" << bad.output;
    for (const std::string& word : c.expectedWords) EXPECT_NE(bad.output.find(word), std::string::npos) << bad.output;
  }
}

TEST_F(RenderCliTest, WindowBackendWithoutDisplaySaysWhatToDo) {
  // Without a display (as in CI, or over ssh) the window backend must explain itself, not crash.
  const RunResult r = runRender("--backend window -o " + quoted(dir / "w.png"), "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("display"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--backend egl"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lgh::test
