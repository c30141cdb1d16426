#pragma once
// lgh-bench build: how long the GPU takes to build the lighting grid hierarchy, in the shape of the
// paper's Table 1 (per-step times, S1 + gather vs scatter into every level) and Table 2 (total time
// vs light count), with the CPU builds (lgh/, double precision) as a reference column and
// device-independent counts (levels, grid lights per level) beside every time.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace lgh::bench {

struct BuildBenchOptions {
  std::vector<size_t> lightCounts{1000, 10000, 100000, 1000000};
  size_t table1Lights = 100000;  // measured too if not in lightCounts
  int levels = 0;                // 0: the automatic count for each light set
  int repeats = 5;
  double budgetSeconds = 60;    // per method and light count: slow methods get fewer repeats
  double cpuLimitSeconds = 30;  // skip a CPU build predicted to take longer than this
  std::string scene;            // empty: the default scene if it exists, else the random box
  bool random = false;
  std::string csvPath, jsonPath;
  bool chunkTest = false;
  size_t chunkTestLights = 4500000;  // 144 MB of GpuLight: more than one 128 MiB storage block
  std::string backend = "auto";
  std::uint32_t seed = 2019;
};

// Registers the `build` subcommand and its options on `app`.
CLI::App* addBuildCommand(CLI::App& app, BuildBenchOptions& options);

// Runs the benchmark and prints its tables. Returns the exit code: 0, or 1 when a sanity check failed
// (the two GPU methods disagree on the levels or on S1, or a level does not carry S0's energy).
int runBuildBench(const BuildBenchOptions& options);

}  // namespace lgh::bench
