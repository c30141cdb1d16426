#pragma once
// What lgh-bench sweep writes: a table per case on stdout, sweep.csv (one row per measurement, medians
// over the repeats) and sweep.json (everything, every repeat and every render setting), the files
// bench/sweep/plot_sweep.py reads.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/sweep/sweep_case.h"

namespace lgh::bench {

// What the JSON says about the run as a whole.
struct SweepRunInfo {
  std::string device;  // the GL context
  int width = 0, height = 0, repeats = 0;
  std::string preset;
  std::vector<std::string> failures;
  size_t samplesRetaken = 0, samplesContended = 0;
};

void printCase(const Case& c);
// Both written to a .tmp file first and renamed, so a reader never sees half a file.
void writeSweepCsv(const std::filesystem::path& path, const std::vector<Case>& cases);
void writeSweepJson(const std::filesystem::path& path, const std::vector<Case>& cases, const SweepRunInfo& info);

// "2026-12-01 16:48": when the sweep ran, local time.
std::string timestamp();

}  // namespace lgh::bench
