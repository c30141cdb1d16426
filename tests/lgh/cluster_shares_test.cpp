// The input lights behind a grid light (lgh/cluster_shares.h): their shares are a partition of each
// input light's importance over every level, and the level-by-level descent draws them with exactly
// those probabilities (chi-square).
#include "lgh/cluster_shares.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "chi_square.h"
#include "test_lights.h"

namespace lgh {
namespace {

using test::kEMin;

// Each input light's importance a_i is spread over the grid lights of every level: summed over a
// level, W_V share_i(V) = a_i, where W_V = lum(I_V) is the grid light's importance. A share that
// composed the levels wrongly (a weight missing, counted twice, or normalised by the wrong total)
// breaks this for some light.
TEST(ClusterShares, EachLevelSplitsEveryLightsImportanceExactly) {
  const std::vector<Light> lights = test::randomCube(300, 7, true);
  for (bool gathered : {true, false}) {
    SCOPED_TRACE(gathered ? "gather" : "scatter");
    const GridGeometry grid = makeGrid(lights, 4, kEMin);
    const Hierarchy h = gathered ? buildGather(lights, grid) : buildScatter(lights, grid);
    const ClusterSources clusters(lights, h, gathered);
    for (int level = 1; level <= 4; ++level) {
      std::vector<double> received(lights.size(), 0.0);
      for (size_t g = 0; g < h.levels[size_t(level)].size(); ++g) {
        const double W = luminance(h.levels[size_t(level)][g].intensity);
        double sum = 0;
        for (const LightShare& s : clusters.shares(level, g)) {
          received[s.light] += W * s.share;
          sum += s.share;
        }
        EXPECT_NEAR(sum, 1.0, 1e-12) << "level " << level << ", grid light " << g;
      }
      for (size_t i = 0; i < lights.size(); ++i)
        EXPECT_NEAR(received[i], luminance(glm::dvec3(lights[i].intensity)), 1e-9)
            << "level " << level << ", light " << i;
    }
  }
}

// The descent a shadow ray would take (a source by weight, then its source, ...) reaches input light
// i with probability share(i), checked on the grid lights of a coarse level with many lights.
TEST(ClusterShares, DescentDrawsLightsByTheirShares) {
  const std::vector<Light> lights = test::randomCube(400, 11, false);
  const GridGeometry grid = makeGrid(lights, 4, kEMin);
  const Hierarchy h = buildGather(lights, grid);
  const ClusterSources clusters(lights, h);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int level = 3;
  int tested = 0;
  for (size_t g = 0; g < h.levels[level].size() && tested < 4; ++g) {
    const std::vector<LightShare> shares = clusters.shares(level, g);
    if (shares.size() < 20) continue;  // a cluster worth testing
    ++tested;
    std::vector<double> counts(shares.size(), 0.0), probabilities(shares.size());
    for (size_t s = 0; s < shares.size(); ++s) probabilities[s] = shares[s].share;
    const int draws = 20000;
    for (int d = 0; d < draws; ++d) {
      const size_t light = clusters.sample(level, g, [&] { return unit(rng); });
      const auto it = std::lower_bound(shares.begin(), shares.end(), light,
                                       [](const LightShare& s, size_t l) { return s.light < l; });
      ASSERT_TRUE(it != shares.end() && it->light == light) << "drew light " << light << " outside the cluster";
      counts[size_t(it - shares.begin())] += 1;
    }
    const test::ChiSquare chi = test::chiSquare(counts, probabilities);
    EXPECT_TRUE(chi.passes()) << "grid light " << g << ": chi-square " << chi.statistic << " with " << chi.dof
                              << " dof (1% critical " << chi.critical01 << ")";
  }
  EXPECT_EQ(tested, 4);
}

}  // namespace
}  // namespace lgh
