#pragma once
// Summaries of repeated timings. The median rather than the mean: on a shared machine a run is now and
// then slowed by something else, and one such outlier should not move the reported number.

#include <algorithm>
#include <vector>

namespace lgh::bench {

struct Spread {
  double median = 0, min = 0, max = 0;
};

inline Spread spreadOf(std::vector<double> samples) {
  if (samples.empty()) return {};
  std::sort(samples.begin(), samples.end());
  const size_t n = samples.size();
  const double median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  return {median, samples.front(), samples.back()};
}

}  // namespace lgh::bench
