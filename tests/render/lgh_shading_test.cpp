// The GLSL shading model (glsl/shared/lgh_shading.glsl) against the C++ reference (lgh/) on the same
// random inputs, including the breakpoints of the blending functions.
#include <random>

#include "gl_test_env.h"
#include "lgh/blending.h"
#include "lgh/shading.h"
#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "shared/bindings.h"
#include "tests/test_types.h"

namespace lgh::test {
namespace {

using gpu::ShadingCase;

class LghShadingTest : public GLTest {};

TEST_F(LghShadingTest, GlslMatchesCppReference) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.0f, 1.0f);
  std::normal_distribution<float> g;
  std::vector<ShadingCase> cases;
  const LevelRole roles[] = {LevelRole::Finest, LevelRole::Middle, LevelRole::Top, LevelRole::Only};
  for (int i = 0; i < 20000; ++i) {
    ShadingCase c;
    const float omni = i % 5 == 0 ? 1.0f : pos(rng) * 0.5f;
    glm::vec3 m = glm::normalize(glm::vec3(g(rng), g(rng), g(rng))) * (1.0f - omni) * pos(rng);
    const float R = 0.1f + pos(rng);
    // Distances at and around every breakpoint (R/2, R, 2R) as well as random ones.
    const float breakpoints[] = {0.0f, 0.5f * R, R, 2.0f * R};
    const float d = i % 4 == 0 ? breakpoints[(i / 4) % 4] : 3.0f * R * pos(rng);
    c.lightPosOmni = glm::vec4(u(rng), u(rng), u(rng), omni);
    c.intensityClamp = glm::vec4(pos(rng), pos(rng), pos(rng), i % 3 == 0 ? 0.0f : 0.2f * pos(rng));
    c.meanNormalD = glm::vec4(m, d);
    c.pointRadius = glm::vec4(u(rng), u(rng), u(rng), R);
    if (i % 50 == 0) c.pointRadius = glm::vec4(glm::vec3(c.lightPosOmni), R);  // light on the point: d = 0
    c.normalRole = glm::vec4(glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), float(i % 4));
    cases.push_back(c);
  }
  gl::Buffer caseBuffer = gl::Buffer::fromVector({"test", "data"}, cases),
             resultBuffer({"test", "results"}, cases.size() * sizeof(glm::vec4));
  caseBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  resultBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  gl::Program::compute("tests/lgh_shading.comp").dispatch1D(cases.size(), 64);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const auto results = resultBuffer.downloadAll<glm::vec4>();

  for (size_t i = 0; i < cases.size(); ++i) {
    const ShadingCase& c = cases[i];
    const glm::dvec3 n(c.normalRole);
    const glm::dvec3 expected =
        lightContribution(glm::dvec3(c.lightPosOmni), glm::dvec3(c.intensityClamp), glm::dvec3(c.meanNormalD),
                          c.lightPosOmni.w, glm::dvec3(c.pointRadius), &n, c.intensityClamp.w);
    const double blend = blendWeight(roles[i % 4], c.meanNormalD.w, c.pointRadius.w);
    ASSERT_NEAR(results[i].a, blend, 1e-6) << "case " << i;
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(results[i][k], expected[k], 1e-4 * std::abs(expected[k]) + 1e-6) << "case " << i;
    ASSERT_TRUE(std::isfinite(results[i].r));
  }
}

}  // namespace
}  // namespace lgh::test
