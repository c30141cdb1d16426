#pragma once
// lgh-bench memory: what a frame holds of the GPU's memory (gl::memory(), the engine's buffers and
// textures), split into what follows the pixels, what follows the lights and what is fixed (each object's
// label says what its size follows), against the input lights (1K to 4.5M, S0 bound in chunks past one
// storage block), the image size, k and interleaving, for both indirect methods, and the hierarchy of
// the same lights in a scene 1,000 times larger. Memory is deterministic: the tables are the same on any
// machine with the same storage block limit, so they go to docs/measurements.md as printed.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "bench/common/bench_setup.h"

namespace lgh::bench {

struct MemoryBenchOptions {
  // --scene, --backend and the render settings but the bench's own (kMemoryOwnSettings).
  RenderBenchOptions render;
  std::vector<double> vplCounts{1e3, 1e4, 1e5, 1e6, 4.5e6};          // VPL budgets of the lights table
  size_t fixedVpls = 100000;                                         // the other tables' budget
  std::vector<std::string> sizes{"320x180", "640x360", "1280x720"};  // the image-size table's
  std::string markdownPath;                                          // also write the tables here
};

inline const std::vector<std::string> kMemoryOwnSettings{"vpls",  "indirect-method", "shadow-samples", "interleave",
                                                         "width", "height",          "accumulate"};

CLI::App* addMemoryCommand(CLI::App& app, MemoryBenchOptions& options);
int runMemoryBench(const MemoryBenchOptions& options);

}  // namespace lgh::bench
