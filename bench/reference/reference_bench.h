#pragma once
// lgh-bench reference: the exact reference of one scene at one VPL target (bench/reference/reference.h: every
// light at every pixel with its true visibility, Embree on the CPU), computed by every rank of the run
// (mpiexec -n N / srun; bench/reference/reference_ranks.h) in tiles kept in the cache as they complete, so that a
// killed run started again computes only the missing tiles. Writes the irradiance as EXR and leaves the
// reference in the cache under the key lgh-bench sweep uses for the same settings: a cluster can make
// the references that a sweep then finds.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

#include "render/settings.h"

namespace lgh::bench {

struct ReferenceBenchOptions {
  std::string scene;        // PATH or PATH@CAMERA
  RenderSettings settings;  // 320 x 180 by default, as the sweep
  size_t vpls = 10000;      // VPL target (the budget is raised until it is met, as the sweep)
  double pixels = 0;        // fraction of the pixels; 0: all unless that exceeds `budget` pairs (as the sweep)
  double budget = 1.6e9;    // pixel-light pairs above which the automatic reference takes a pixel subset
  int tileSize = 32;        // pixels per tile side
  unsigned threads = 0;     // Embree workers per rank (0: the host's hardware threads / its ranks)
  std::string cacheDir;     // default: reference-cache beside lgh-bench (the sweep's); "none": no cache
  std::string out;          // EXR of the shadowed irradiance (alpha: 1 where computed); empty: none
  std::string backend = "auto";
  int killAfterTiles = -1, failTile = -1;  // test hooks (hidden options)
};

CLI::App* addReferenceCommand(CLI::App& app, ReferenceBenchOptions& options);
int runReferenceBench(const ReferenceBenchOptions& options);

}  // namespace lgh::bench
