#include "lgh/shading.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "test_lights.h"

namespace lgh {
namespace {

// Integral of f(u) over the unit sphere by the midpoint rule on an equal-area (z, phi) grid.
template <typename F>
double integrateOverSphere(F&& f, int zSteps = 200, int phiSteps = 400) {
  const double pi = glm::pi<double>();
  const double cellArea = (2.0 / zSteps) * (2.0 * pi / phiSteps);
  double sum = 0.0;
  for (int i = 0; i < zSteps; ++i) {
    const double z = -1.0 + (i + 0.5) * 2.0 / zSteps;
    const double r = std::sqrt(1.0 - z * z);
    for (int j = 0; j < phiSteps; ++j) {
      const double phi = (j + 0.5) * 2.0 * pi / phiSteps;
      sum += f(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
    }
  }
  return sum * cellArea;
}

// A cluster with a share o of omni intensity emits pi (1 + 3o) per unit of total intensity, however
// its normals are spread (|m| from 0 to its maximum 1 - o).
TEST(Shading, EmissionLobeConservesFlux) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<glm::dvec3, double>> clusters = {
      {glm::dvec3(0.0), 0.0}, {glm::dvec3(0.0), 1.0}, {glm::dvec3(0.0, 0.0, 1.0), 0.0}, {glm::dvec3(0.0), 0.5}};
  for (int i = 0; i < 40; ++i) {
    const double o = unit(rng);
    clusters.emplace_back(test::randomUnitVector(rng) * (1.0 - o) * unit(rng), o);
  }
  for (const auto& [m, o] : clusters) {
    const double flux = integrateOverSphere([&, m = m, o = o](const glm::dvec3& u) { return emissionLobe(m, o, u); });
    EXPECT_NEAR(flux, glm::pi<double>() * (1.0 + 3.0 * o), 1e-3) << "|m| = " << glm::length(m) << ", o = " << o;
  }
}

TEST(Shading, EmissionLobeOfOneVplIsItsCosineAndOfOmniLightsIsOne) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec3 n = test::randomUnitVector(rng), u = test::randomUnitVector(rng);
    EXPECT_NEAR(emissionLobe(n, 0.0, u), std::max(0.0, glm::dot(n, u)), 1e-15);
    EXPECT_DOUBLE_EQ(emissionLobe(glm::dvec3(0.0), 1.0, u), 1.0);
    EXPECT_GE(emissionLobe(n * 0.3, 0.2, u), 0.0);
  }
}

TEST(Shading, FollowsTheInverseSquareLawOutsideTheClamp) {
  const glm::dvec3 I(1.0, 2.0, 3.0), n(0.0);
  const glm::dvec3 x(0.0);
  const glm::dvec3 near = lightContribution(glm::dvec3(0.0, 0.0, 1.0), I, n, 1.0, x, nullptr, 0.1);
  const glm::dvec3 far = lightContribution(glm::dvec3(0.0, 0.0, 2.0), I, n, 1.0, x, nullptr, 0.1);
  EXPECT_NEAR(glm::distance(near, I), 0.0, 1e-15);
  EXPECT_NEAR(glm::distance(far, I / 4.0), 0.0, 1e-15);
  // Inside the clamp distance the falloff stops at 1/dc².
  const glm::dvec3 clamped = lightContribution(glm::dvec3(0.0, 0.0, 0.05), I, n, 1.0, x, nullptr, 0.1);
  EXPECT_NEAR(glm::distance(clamped, I / 0.01), 0.0, 1e-12);
}

TEST(Shading, ReceiverCosineAndEmitterDirectionHaveTheRightSigns) {
  const glm::dvec3 I(1.0), up(0.0, 0.0, 1.0), down(0.0, 0.0, -1.0);
  const glm::dvec3 vpl(0.0);  // a VPL at the origin facing +z
  // A receiver above it, facing it, gets I / d²; one below gets nothing (behind the emitter),
  // and so does one above that faces away.
  EXPECT_DOUBLE_EQ(lightContribution(vpl, I, up, 0.0, glm::dvec3(0.0, 0.0, 2.0), &down, 0.0).x, 0.25);
  EXPECT_EQ(lightContribution(vpl, I, up, 0.0, glm::dvec3(0.0, 0.0, -2.0), &up, 0.0).x, 0.0);
  EXPECT_EQ(lightContribution(vpl, I, up, 0.0, glm::dvec3(0.0, 0.0, 2.0), &up, 0.0).x, 0.0);
  // x is 60 degrees off the VPL's normal at d = 2: the emitter's cosine is 1/2.
  const glm::dvec3 x(std::sqrt(3.0), 0.0, 1.0);
  const glm::dvec3 facingLight = -glm::normalize(x), facingMinusX(-1.0, 0.0, 0.0);
  EXPECT_NEAR(lightContribution(vpl, I, up, 0.0, x, &facingLight, 0.0).x, 0.5 / 4.0, 1e-15);
  // A receiver facing -x sees the light 30 degrees off its normal: cosine sqrt(3)/2.
  EXPECT_NEAR(lightContribution(vpl, I, up, 0.0, x, &facingMinusX, 0.0).x, std::sqrt(3.0) / 2.0 * 0.5 / 4.0, 1e-15);
}

TEST(Shading, CoincidentLightAndPointStayFinite) {
  const glm::dvec3 p(1.0, 2.0, 3.0), I(1e8), up(0.0, 0.0, 1.0);
  for (double clamp : {0.0, 0.01}) {
    for (const glm::dvec3* nx : {static_cast<const glm::dvec3*>(nullptr), &up}) {
      for (const auto& [m, o] : {std::pair{glm::dvec3(0.0), 1.0}, std::pair{up, 0.0}, std::pair{-up, 0.0}}) {
        const glm::dvec3 c = lightContribution(p, I, m, o, p, nx, clamp);
        EXPECT_TRUE(test::isFinite(c));
        EXPECT_GE(c.x, 0.0);
      }
    }
  }
  // With a clamp, d = 0 is just the clamped value of a light in front.
  EXPECT_DOUBLE_EQ(lightContribution(p, glm::dvec3(1.0), glm::dvec3(0.0), 1.0, p, &up, 0.5).x, 4.0);
}

}  // namespace
}  // namespace lgh
