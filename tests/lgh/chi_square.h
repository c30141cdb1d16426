#pragma once

// Pearson's chi-square test of observed counts against expected probabilities, shared by the CPU and
// GPU sampling tests.

#include <algorithm>
#include <cmath>
#include <vector>

namespace lgh::test {

struct ChiSquare {
  double statistic = 0;
  int dof = 0;
  double critical01 = 0;  // the statistic exceeds it with probability 1% when the counts follow the probabilities
  bool passes() const { return statistic < critical01; }
};

// The statistic's 1% critical value: Wilson and Hilferty's cube-root approximation (within 1% for dof >= 3).
inline double chiSquareCritical01(int dof) {
  const double k = std::max(dof, 1);
  return k * std::pow(1.0 - 2.0 / (9.0 * k) + 2.3263 * std::sqrt(2.0 / (9.0 * k)), 3.0);
}

// Bins whose expected count is below 5 are pooled into one (the test's usual validity condition).
inline ChiSquare chiSquare(const std::vector<double>& counts, const std::vector<double>& probabilities) {
  double total = 0;
  for (double c : counts) total += c;
  ChiSquare result;
  double pooledObserved = 0, pooledExpected = 0;
  int bins = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    const double expected = total * probabilities[i];
    if (expected < 5) {
      pooledObserved += counts[i];
      pooledExpected += expected;
      continue;
    }
    result.statistic += (counts[i] - expected) * (counts[i] - expected) / expected;
    ++bins;
  }
  if (pooledExpected > 0) {
    result.statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
    ++bins;
  }
  result.dof = bins - 1;
  result.critical01 = chiSquareCritical01(result.dof);
  return result;
}

// Independent chi-square tests pooled into one: the sum of their statistics is chi-square distributed with
// the sum of their degrees of freedom, so a family of tests keeps a single 1% false-alarm rate instead of
// one per test (16 tests at 1% each fail a correct sampler 15% of the time).
inline ChiSquare pooledChiSquare(const std::vector<ChiSquare>& tests) {
  ChiSquare result;
  for (const ChiSquare& t : tests) result.statistic += t.statistic, result.dof += t.dof;
  result.critical01 = chiSquareCritical01(result.dof);
  return result;
}

}  // namespace lgh::test
