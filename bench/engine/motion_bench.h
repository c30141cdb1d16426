#pragma once
// lgh-bench motion: an animated sequence (the scene's glTF animation, or the motions of
// render/scene/scripted_motion.h) rendered frame by frame by several configurations side by side (the LGH
// without history, with the paper's ratio-only history, with the per-pixel tested history; its VPLs redrawn
// each frame; the lightcuts without and with history), each frame held to the exact reference of that frame
// (bench/sweep/sweep_reference.h: Embree over the frame's S0, on a pixel subset, cached, in tiles, on MPI
// ranks), and reported per frame and over the sequence:
//   error          relative RMSE of the shadowed indirect irradiance's luminance, sqrt(sum (I - R)^2 / sum R^2)
//   temporal error the same measure of the frame-to-frame change, sqrt(sum (dI - dR)^2 / sum R^2) with
//                  dI = I_t - I_t-1 and dR = R_t - R_t-1: flicker (changes the reference does not make) and
//                  lag (changes it makes that the image does not) both count, noise that stays put does not
// The reference is the exact sum over the frame's S0 drawn with the run's seed: the VPLs of the configurations
// that draw the same random numbers; the redrawn ones are held to it too (their S0 is another estimate of
// the same light).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "bench/common/bench_setup.h"

namespace lgh::bench {

struct MotionBenchOptions {
  RenderBenchOptions render;  // --scene, --backend and the render settings but kMotionOwnSettings
  int frames = 64;
  double fps = 30.0, startTime = -1.0;  // startTime < 0: the animation's start
  std::string sunStep, pointStep;       // render/scene/scripted_motion.h
  double orbitStep = 0.0;
  int lightcutSamples = 8;        // the lightcuts' samples per pixel (0: no lightcut configurations)
  double referencePixels = 0.25;  // share of the pixels the reference computes
  std::string referenceCache;     // empty: the default cache (defaultReferenceCache)
  std::string csvPath;            // per frame and configuration
  std::string imageDir;           // each frame's tested-history image beside the reference's (full references)
};

inline const std::vector<std::string> kMotionOwnSettings{"accumulate", "accumulate-motion", "indirect-method"};

CLI::App* addMotionCommand(CLI::App& app, MotionBenchOptions& options);
int runMotionBench(const MotionBenchOptions& options);

}  // namespace lgh::bench
