#pragma once
// lgh-bench light: what the LGH light pass costs as the light count grows, in the shape of the paper's
// Fig. 5 and Sec. 5: fragments rasterized per pixel (overdraw) and light-pass time for 1K .. 1M VPLs
// on one scene, beside the brute-force pass (every VPL at every pixel) where it finishes; then
// interleaved sampling 1x1 / 2x2 / 4x4 at one VPL count, time and error measured in the same run.
// Each VPL count and tiling is measured with the paper's cube volumes and with culled volumes
// (LightPassSettings::volumeCulling), alternating frame by frame so that both see the same machine.

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace lgh::bench {

struct LightBenchOptions {
  std::string scene;      // empty: ../shared/scenes/sponza_sun if present, else the project's Cornell box
  std::string camera;
  int width = 320, height = 180;
  std::vector<size_t> vplCounts{1000, 10000, 100000, 1000000};
  int bounces = 1;
  float alpha = 1.0f;
  float clampDistance = 0.0f;  // 0: the renderer's default (1e-2 of the scene diagonal)
  int startLevel = 1;
  std::vector<int> tiles{1, 4};    // interleaving factors of the VPL-count sweep
  int repeats = 3;
  size_t bruteForceLimit = 20000;   // brute-force light pass timed up to this many input lights
  size_t interleaveVpls = 100000;   // 0: skip the interleaving table
  bool exactError = true;           // interleaving table: relative RMSE against the exact sum too
  std::string csvPath, jsonPath;
  std::string backend = "auto";
};

CLI::App* addLightCommand(CLI::App& app, LightBenchOptions& options);
// Returns 0, or 1 when a sanity check failed (NaN pixels, interleaving losing more than 1% of the energy).
int runLightBench(const LightBenchOptions& options);

}  // namespace lgh::bench
