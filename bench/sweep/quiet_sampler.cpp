#include "bench/sweep/quiet_sampler.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <thread>

namespace lgh::bench {

QuietSampler::Clock QuietSampler::now() {
  Clock c;
  c.wall = std::chrono::steady_clock::now();
  std::ifstream stat("/proc/stat");
  std::string label;
  unsigned long long v[8] = {};
  if (stat >> label >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7] && label == "cpu")
    c.busyMs = double(v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) * 1000.0 / double(std::max(1L, sysconf(_SC_CLK_TCK)));
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  c.ownMs = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 +
            double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
  return c;
}

// /proc/stat counts 10 ms ticks: two ticks per core are forgiven as rounding.
double QuietSampler::othersShare(const Clock& a, const Clock& b) {
  if (a.busyMs == 0 && b.busyMs == 0) return 0;
  const double cores = double(std::max(1u, std::thread::hardware_concurrency()));
  const double wall = std::chrono::duration<double, std::milli>(b.wall - a.wall).count();
  const double others = (b.busyMs - a.busyMs) - (b.ownMs - a.ownMs) - 20.0 * cores;
  return std::clamp(others / std::max(wall * cores, 1e-9), 0.0, 1.0);
}

void QuietSampler::waitForQuiet() {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < std::chrono::minutes(2)) {
    const Clock before = now();
    std::this_thread::sleep_for(std::chrono::seconds(1));
    if (othersShare(before, now()) < 0.1) return;
  }
}

}  // namespace lgh::bench
