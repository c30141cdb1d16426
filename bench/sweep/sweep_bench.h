#pragma once
// lgh-bench sweep: the speed/accuracy trade (docs/design.md §7). Renders a grid of parameters (alpha, start
// level, interleaving, k, shadow filter) on one or more scenes and VPL counts, repeats each point,
// and measures every image against the exact reference of bench/reference/reference.h (Embree, CPU):
// relative RMSE and PSNR of the unshadowed irradiance and of the shadowed one (irradiance x
// visibility ratio), beside per-pass times, overdraw and grid lights. In the same run it measures
// the baselines every LGH point is compared with: brute force over all S0 lights (rasterized, every
// light full-screen; shadowed, one ray per light and pixel through the GPU BVH) and uniform VPL
// subsampling (brute force over a random M of the N lights, scaled by N / M), unshadowed, with
// exact visibility per light, and with the frame's own shadow estimate. Writes sweep.csv and
// sweep.json (and .npy images for the plots); bench/sweep/plot_sweep.py turns them into plots and the
// numbers in docs/measurements.md. A progress bar with the time left goes to stderr.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "render/settings.h"

namespace lgh::bench {

struct SweepOptions {
  std::string preset;               // "readme", "smoke" or empty: what the unset options default to
  std::vector<std::string> scenes;  // glTF paths, each optionally PATH@CAMERA
  // Every measurement's base settings: --width, --bounces, ... (render/settings.h) but the sweep's own
  // (kSweepOwnSettings). The sweep's default image is 320 x 180 (set by addSweepCommand).
  RenderSettings settings;
  std::vector<size_t> vpls{10000};  // VPL targets; the budget (inputLights.vpls) is raised until they are met
  // The LGH grid: every combination of these (a preset may use a union of smaller grids instead).
  std::vector<float> alphas{0.5f, 1.0f, 2.0f, 4.0f};
  std::vector<int> startLevels{0, 1};
  std::vector<int> interleave{1, 4};
  std::vector<int> shadowSamples{4};
  std::vector<std::string> filter{"on"};  // on: the a-trous filter (filter-passes); off: the raw ratio
  std::vector<int> frames{1};             // still frames accumulated per measurement (the last is measured)
  // The stochastic lightcuts' grid (with the same filter and frames lists): samples n x blocks B x
  // interleave m; no samples: no lightcut points.
  std::vector<int> rtslcSamples;
  std::vector<int> rtslcBlocks{8};
  std::vector<int> rtslcInterleave{1};
  int repeats = 3;
  // Reference: pixel fraction (0: automatic, all pixels unless that exceeds referenceBudget pairs).
  double referencePixels = 0;
  double referenceBudget = 1.6e9;  // pixel-light pairs of a full-image reference before subsetting
  // Baselines: subset sizes M of uniform subsampling: unshadowed (and, with the frame's shadow
  // estimate, a fresh set of about M lights), and with exact visibility per light.
  std::vector<size_t> uniformLights{16, 64, 256, 1024, 4096};
  std::vector<size_t> uniformShadowedLights{2, 4, 8, 16, 32, 64};
  size_t bruteForceLimit = 30000;   // full brute force measured up to this many S0 lights, else extrapolated
  std::vector<size_t> scalingVpls;  // time and overdraw vs VPL count (alpha 1, S1, k 4, 1x1 and 4x4), no error
  std::string outDir;               // default: <source>/bench/results for the readme preset, else ./sweep-results
  std::string cacheDir;             // default: reference-cache beside the executable; "none": no cache
  bool images = true;               // .npy images (reference, every point) for the strip plot, full references only
  unsigned threads = 0;             // reference workers per rank (0: this host's hardware threads / its ranks)
  int tileSize = 32;                // reference tiles (pixels per side), each kept in the cache as it completes
  int retries = 3;  // a timed sample during which other processes took > 25% of the machine is taken again
  std::string backend = "auto";
  std::vector<std::string> set;  // NAME=VALUE: any other render setting, as the --NAME options
  CLI::App* command = nullptr;   // set by addSweepCommand: tells given options from defaults
};

// The render settings the sweep sets itself: the grid's (lists: --vpls, --alpha, ...), the camera
// (--scene PATH@CAMERA) and the measurements' own (overdraw, brute force). No --set for them.
inline const std::vector<std::string> kSweepOwnSettings{
    "camera",   "vpls",        "alpha",           "start-level",   "interleave",  "shadow-samples",
    "overdraw", "brute-force", "indirect-method", "rtslc-samples", "rtslc-block", "rtslc-interleave"};

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options);
// Returns 0, or 1 when a check failed: NaN/Inf pixels or errors, the GL brute force disagreeing with
// the reference (1e-4 relative), or the unshadowed error not falling with alpha at start level 0.
int runSweepBench(SweepOptions options);

}  // namespace lgh::bench
