#pragma once
// Shared set-up for GL tests: the process-wide debug context and paths to test data.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "render/gl/context.h"
#include "render/gl/debug.h"
#include "render/gl/gl.h"

namespace lgh::test {

gl::Context& glContext();

// Fixture for tests that issue GL calls: makes the context current, fails on any GL error.
class GLTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
};

inline std::filesystem::path sourceDir() { return LGH_SOURCE_DIR; }
inline std::filesystem::path sharedScenesDir() { return LGH_SHARED_SCENES_DIR; }

// Path to a scene in ../shared/scenes, or GTEST_SKIP() with the reason when that folder is absent.
#define LGH_REQUIRE_SHARED_SCENE(var, relativePath)                                  \
  const std::filesystem::path var = ::lgh::test::sharedScenesDir() / (relativePath); \
  if (!std::filesystem::exists(var))                                                 \
  GTEST_SKIP() << "needs " << var.string() << " (../shared/scenes is not beside this checkout)"

}  // namespace lgh::test
