// lgh-render as a user runs it: each backend renders the default scene, outputs are valid images,
// and every kind of bad input ends with a non-zero exit and a message naming the problem.
#include <OpenImageIO/imageio.h>

#include <array>
#include <cstdio>
#include <sys/wait.h>

#include "gl_test_env.h"
#include "gltf_writer.h"

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

TEST_F(RenderCliTest, WindowBackendWithoutDisplaySaysWhatToDo) {
  // Without a display (as in CI, or over ssh) the window backend must explain itself, not crash.
  const RunResult r = runRender("--backend window -o " + quoted(dir / "w.png"), "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("display"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--backend egl"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lgh::test
