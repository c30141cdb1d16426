#pragma once
// lgh-bench frame: a whole frame split by pass, in the shape of the paper's Table 3 (G-buffer, VPLs,
// build, light pass, shadow rays, filter, composite) for interleaving 1x1, 2x2 and 4x4, measured in
// one run, with the device-independent counts beside the times; then the stochastic lightcuts' frame on
// the same lights (tree build as [LY20]'s Table 1, cuts shared by 8x8 blocks and per pixel, sampling).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "bench/common/bench_setup.h"

namespace lgh::bench {

struct FrameBenchOptions {
  // --scene, --backend and the render settings (--width, --vpls, --shadow-samples, ...: render/settings.h)
  // but the bench's own (kFrameOwnSettings). --vpls is the VPL count to reach: the budget is raised
  // until the VPLs made meet it. Its default where it differs from RenderSettings' (set by
  // addFrameCommand): one bounce.
  RenderBenchOptions render;
  std::vector<int> interleave{1, 2, 4};
  int repeats = 3;
  bool compareCubes = true;    // also time the light pass with the paper's cube volumes, frame by frame
  bool compareTargets = true;  // also time the shadow rays aimed at the paper's jittered cluster centres
  bool splitRays = true;       // also time the shadow-ray pass untraced: its time split into tracing and the rest
  // The stochastic lightcuts' frame (--indirect-method rtslc) at this many samples per pixel, with 8x8 shared
  // and per-pixel cuts, and its tree build step by step (the paper's Table 1); 0: none.
  int lightcutSamples = 8;
  std::string csvPath;
};

// Settings the bench sets itself: the interleaving factors (a list, --interleave), and the overdraw
// counter it switches on for its warm-up frames.
inline const std::vector<std::string> kFrameOwnSettings{"interleave", "overdraw", "indirect-method", "rtslc-samples",
                                                        "rtslc-block"};

CLI::App* addFrameCommand(CLI::App& app, FrameBenchOptions& options);
int runFrameBench(const FrameBenchOptions& options);

}  // namespace lgh::bench
