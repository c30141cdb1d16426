#pragma once
// lgh-bench frame: a whole frame split by pass, in the shape of the paper's Table 3 (G-buffer, VPLs,
// build, light pass, shadow rays, filter, composite) for interleaving 1x1, 2x2 and 4x4, measured in
// one run, with the device-independent counts beside the times.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace lgh::bench {

struct FrameBenchOptions {
  std::string scene;  // empty: ../shared/scenes/sponza_sun if present, else the project's Cornell box
  std::string camera;
  int width = 640, height = 360;
  int vpls = 100000;
  int bounces = 1;
  int shadowSamples = 4;
  float alpha = 1.0f;
  std::vector<int> interleave{1, 2, 4};
  int repeats = 3;
  bool compareCubes = true;  // also time the light pass with the paper's cube volumes, frame by frame
  std::string csvPath;
  std::string backend = "auto";
};

CLI::App* addFrameCommand(CLI::App& app, FrameBenchOptions& options);
int runFrameBench(const FrameBenchOptions& options);

}  // namespace lgh::bench
