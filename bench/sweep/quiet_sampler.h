#pragma once
// Timed samples on a shared machine. Times measured minutes apart compare only if nothing else ran
// meanwhile: a sample during which other processes used more than a quarter of the machine is taken
// again once the machine is quiet.

#include <chrono>
#include <cstddef>

#include "render/gl/gl.h"

namespace lgh::bench {

// Wall milliseconds of fn() between two glFinish calls.
template <typename Fn>
double timedMs(Fn&& fn) {
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  fn();
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

class QuietSampler {
 public:
  static constexpr double kBusyLimit = 0.25;  // others' largest share of the machine during a kept sample

  explicit QuietSampler(int retries) : retries_(retries) {}

  // Runs sample() (one timed measurement) until other processes stayed under kBusyLimit of the
  // machine while it ran, at most 1 + retries times, each retry once the machine has been quiet for a
  // second (waiting up to 2 minutes); returns their share during the last run.
  template <typename Fn>
  double sample(Fn&& fn) {
    double share = 0;
    for (int attempt = 0; attempt <= retries_; ++attempt) {
      if (attempt > 0) {
        ++retaken_;
        waitForQuiet();
      }
      const Clock before = now();
      fn();
      share = othersShare(before, now());
      if (share <= kBusyLimit) break;
    }
    if (share > kBusyLimit) ++contended_;
    return share;
  }

  int retries() const { return retries_; }
  size_t retaken() const { return retaken_; }      // samples taken again
  size_t contended() const { return contended_; }  // samples still contended after the last try

 private:
  struct Clock {
    double busyMs = 0;  // every CPU, every process (/proc/stat; 0 where there is none)
    double ownMs = 0;   // this process, all its threads (llvmpipe's included)
    std::chrono::steady_clock::time_point wall;
  };
  static Clock now();
  // The share of the machine (0..1) other processes used between a and b.
  static double othersShare(const Clock& a, const Clock& b);
  // Sleeps until other processes used under 10% of the machine for a whole second (at most 2 minutes).
  static void waitForQuiet();

  int retries_;
  size_t retaken_ = 0, contended_ = 0;
};

}  // namespace lgh::bench
