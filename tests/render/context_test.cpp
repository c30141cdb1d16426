// The GL context layer: every headless backend gives a GL 4.5 core context that runs compute
// shaders, errors surface as exceptions, and bad backend names say what the choices are.
#include <vector>

#include "gl_test_env.h"
#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "shared/bindings.h"

namespace lgh::test {
namespace {

// Runs glsl/tests/scale_buffer.comp on n values and checks every element.
void expectScaleKernelWorks(size_t n) {
  std::vector<float> values(n);
  for (size_t i = 0; i < n; ++i) values[i] = float(i % 7);
  gl::Buffer buffer = gl::Buffer::fromVector({"test", "data"}, values);
  gl::Program program = gl::Program::compute("tests/scale_buffer.comp");
  program.set("factor", 2.0f);
  program.set("count", unsigned(n));
  buffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  program.dispatch1D(n, 64);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<float> out = buffer.downloadAll<float>();
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(out[i], float(i % 7) * 2.0f + float(i)) << "element " << i;
}

class ContextTest : public GLTest {};

TEST_F(ContextTest, IsCore45WithComputeShaders) {
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  expectScaleKernelWorks(1000);
}

TEST_F(ContextTest, DispatchBeyond65535GroupsFoldsIntoY) {
  // 64 * 70000 invocations need more than 65535 groups in x.
  expectScaleKernelWorks(64 * 70000 + 3);
}

TEST_F(ContextTest, DebugErrorsBecomeExceptions) {
  glBindBuffer(GL_ARRAY_BUFFER, 0x7fffffff);  // not a buffer name: GL_INVALID_OPERATION
  EXPECT_THROW(gl::checkErrors("deliberate error"), gl::Error);
  EXPECT_NO_THROW(gl::checkErrors("after"));
}

TEST_F(ContextTest, ShaderCompileErrorNamesTheFile) {
  try {
    gl::Program::compute("tests/does_not_exist.comp");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tests/does_not_exist.comp"), std::string::npos) << e.what();
  }
}

TEST(ContextNames, UnknownBackendListsAlternatives) {
  try {
    gl::parseBackend("vulkan");
    FAIL() << "expected an exception";
  } catch (const gl::ContextError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("vulkan"), std::string::npos);
    for (const auto& name : gl::backendNames()) EXPECT_NE(msg.find(name), std::string::npos) << msg;
  }
}

// Each EGL platform on its own, then back to the shared context: glad's entry points must follow
// whichever context is current. OSMesa is exercised in a separate process (render_cli_test):
// Mesa 22.3 fails to compile shaders in an OSMesa context created after an EGL one in the same
// process (two llvmpipe instances), and a real program uses one backend anyway.
class BackendTest : public ::testing::TestWithParam<gl::Backend> {};

TEST_P(BackendTest, CreatesContextAndRunsCompute) {
  gl::ContextOptions options;
  options.backend = GetParam();
  options.debug = true;
  std::unique_ptr<gl::Context> context;
  try {
    context = gl::Context::create(options);
  } catch (const gl::ContextError& e) {
    if (GetParam() == gl::Backend::EglDevice) GTEST_SKIP() << e.what();
    FAIL() << e.what();
  }
  SCOPED_TRACE(context->description());
  expectScaleKernelWorks(5000);
  EXPECT_NO_THROW(gl::checkErrors("backend test"));
  context.reset();
  glContext().makeCurrent();
  expectScaleKernelWorks(100);
}

INSTANTIATE_TEST_SUITE_P(Headless, BackendTest, ::testing::Values(gl::Backend::EglSurfaceless, gl::Backend::EglDevice),
                         [](const auto& info) {
                           std::string name = gl::backendName(info.param);
                           name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                           return name;
                         });

}  // namespace
}  // namespace lgh::test
