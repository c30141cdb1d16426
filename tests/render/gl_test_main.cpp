// GoogleTest main for GL tests: one debug GL context for the whole process (creating one costs
// 12–34 ms and some drivers dislike many), chosen by LGH_TEST_BACKEND (default: auto).
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

#include "gl_test_env.h"

namespace lgh::test {

gl::Context& glContext() {
  static std::unique_ptr<gl::Context> context = [] {
    gl::ContextOptions options;
    if (const char* backend = std::getenv("LGH_TEST_BACKEND")) options.backend = gl::parseBackend(backend);
    options.debug = true;
    auto ctx = gl::Context::create(options);
    std::cout << "[ GL       ] " << ctx->description() << std::endl;
    return ctx;
  }();
  return *context;
}

void GLTest::SetUp() {
  glContext().makeCurrent();
  gl::checkErrors("before test");
}

void GLTest::TearDown() {
  // A KHR_debug error anywhere in the test fails it here, with the driver's message.
  EXPECT_NO_THROW(gl::checkErrors("end of test"));
}

}  // namespace lgh::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
