#pragma once
// lgh-bench light: what the LGH light pass costs as the light count grows, in the shape of the paper's
// Fig. 5 and Sec. 5: fragments rasterized per pixel (overdraw) and light-pass time for 1K .. 1M VPLs
// on one scene, beside the brute-force pass (every VPL at every pixel) where it finishes; then
// interleaved sampling 1x1 / 2x2 / 4x4 at one VPL count, time and error measured in the same run.
// Each VPL count and tiling is measured with the paper's cube volumes and with culled volumes
// (LightPassSettings::volumeCulling), alternating frame by frame so that both see the same machine.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "bench/common/bench_setup.h"

namespace lgh::bench {

struct LightBenchOptions {
  // --scene, --backend and the render settings (--width, --alpha, --bounces, ...: render/settings.h)
  // but the bench's own (kLightOwnSettings). Its defaults where they differ from RenderSettings' (set
  // by addLightCommand): a 320 x 180 image, one bounce.
  RenderBenchOptions render;
  std::vector<size_t> vplCounts{1000, 10000, 100000, 1000000};
  std::vector<int> tiles{1, 4};  // interleaving factors of the VPL-count sweep
  int repeats = 3;
  size_t bruteForceLimit = 20000;  // brute-force light pass timed up to this many input lights
  size_t interleaveVpls = 100000;  // 0: skip the interleaving table
  bool exactError = true;          // interleaving table: relative RMSE against the exact sum too
  std::string csvPath, jsonPath;
};

// Settings the bench sets itself: the VPL counts (a list, --vpls), the interleaving factors (--tiles and
// the interleaving table's), the volume path it compares, and the overdraw counter and brute force it
// switches per measurement.
inline const std::vector<std::string> kLightOwnSettings{"vpls", "interleave", "volume-culling", "overdraw",
                                                        "brute-force"};

CLI::App* addLightCommand(CLI::App& app, LightBenchOptions& options);
// Returns 0, or 1 when a sanity check failed (NaN pixels, interleaving losing more than 1% of the energy).
int runLightBench(const LightBenchOptions& options);

}  // namespace lgh::bench
