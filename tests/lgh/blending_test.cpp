#include "lgh/blending.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "lgh/grid.h"

namespace lgh {
namespace {

// Sum of the weights of levels firstLevel..L at distance d.
double weightSum(const GridGeometry& grid, int firstLevel, double alpha, double d) {
  double sum = 0.0;
  for (int level = firstLevel; level <= grid.levels; ++level)
    sum += blendWeight(levelRole(level, firstLevel, grid.levels), d, grid.radius(level, alpha));
  return sum;
}

TEST(Blending, RolesFollowPositionInTheUsedRange) {
  EXPECT_EQ(levelRole(1, 1, 1), LevelRole::Only);
  EXPECT_EQ(levelRole(0, 0, 0), LevelRole::Only);
  EXPECT_EQ(levelRole(0, 0, 3), LevelRole::Finest);
  EXPECT_EQ(levelRole(1, 0, 3), LevelRole::Middle);
  EXPECT_EQ(levelRole(2, 0, 3), LevelRole::Middle);
  EXPECT_EQ(levelRole(3, 0, 3), LevelRole::Top);
  EXPECT_EQ(levelRole(1, 1, 2), LevelRole::Finest);
  EXPECT_EQ(levelRole(2, 1, 2), LevelRole::Top);
}

TEST(Blending, MatchesTheTableInsideEachBand) {
  const double R = 3.0;
  struct Row {
    LevelRole role;
    double w0, wQuarter, wThreeQuarters, wOneAndHalf, wThree;
  };
  const Row rows[] = {
      {LevelRole::Finest, 1.0, 1.0, 1.0, 0.5, 0.0},
      {LevelRole::Middle, 0.0, 0.0, 0.5, 0.5, 0.0},
      {LevelRole::Top, 0.0, 0.0, 0.5, 1.0, 1.0},
      {LevelRole::Only, 1.0, 1.0, 1.0, 1.0, 1.0},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(int(row.role));
    EXPECT_DOUBLE_EQ(blendWeight(row.role, 0.0, R), row.w0);
    EXPECT_DOUBLE_EQ(blendWeight(row.role, 0.25 * R, R), row.wQuarter);
    EXPECT_DOUBLE_EQ(blendWeight(row.role, 0.75 * R, R), row.wThreeQuarters);
    EXPECT_DOUBLE_EQ(blendWeight(row.role, 1.5 * R, R), row.wOneAndHalf);
    EXPECT_DOUBLE_EQ(blendWeight(row.role, 3.0 * R, R), row.wThree);
  }
}

// Every weight is continuous: a jump would show up as a seam in the image where d crosses a band.
TEST(Blending, IsContinuousAtTheBreakpoints) {
  const double R = 0.7;
  for (LevelRole role : {LevelRole::Finest, LevelRole::Middle, LevelRole::Top}) {
    for (double breakpoint : {0.5 * R, R, 2.0 * R}) {
      const double below = blendWeight(role, breakpoint * (1.0 - 1e-9), R);
      const double above = blendWeight(role, breakpoint * (1.0 + 1e-9), R);
      EXPECT_NEAR(below, above, 1e-8) << "role " << int(role) << " at " << breakpoint / R << " R";
    }
  }
}

TEST(Blending, ZeroRadiusNeverDividesByZero) {
  for (LevelRole role : {LevelRole::Finest, LevelRole::Middle, LevelRole::Top, LevelRole::Only})
    for (double d : {0.0, 1e-300, 1.0}) EXPECT_TRUE(std::isfinite(blendWeight(role, d, 0.0)));
}

// The weights of the used levels sum to 1 at every distance: exact breakpoints of every level, d = 0,
// huge d, and 1e5 random distances log-uniform over the whole range of radii.
TEST(Blending, PartitionOfUnity) {
  std::mt19937_64 rng(1);
  for (double alpha : {0.25, 0.5, 1.0, 2.0, 4.0, 16.0}) {
    for (int levels = 1; levels <= 12; ++levels) {
      GridGeometry grid;
      grid.topCellSize = 1.7;
      grid.levels = levels;
      for (int firstLevel : {0, 1}) {
        std::vector<double> distances = {0.0, 1e30, std::numeric_limits<double>::max()};
        for (int level = firstLevel; level <= levels; ++level) {
          const double R = grid.radius(level, alpha);
          distances.insert(distances.end(), {0.5 * R, R, 2.0 * R});
        }
        const double lowest = std::log(grid.radius(firstLevel, alpha) * 1e-3);
        const double highest = std::log(grid.radius(levels, alpha) * 1e3);
        std::uniform_real_distribution<double> logDistance(lowest, highest);
        for (int i = 0; i < 100000; ++i) distances.push_back(std::exp(logDistance(rng)));

        for (double d : distances) {
          const double sum = weightSum(grid, firstLevel, alpha, d);
          if (std::abs(sum - 1.0) > 1e-12) {
            FAIL() << "sum " << sum << " at d = " << d << ", alpha " << alpha << ", L " << levels << ", first level "
                   << firstLevel;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace lgh
