#pragma once
// What lgh-bench sweep records: a case (one scene at one VPL target, or the scaling series of a scene)
// and its measurements, every repeat kept; the outputs (bench/sweep/sweep_output.h) summarise them.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bench/sweep/sweep_grid.h"
#include "bench/sweep/sweep_stats.h"
#include "render/renderer.h"

namespace lgh::bench {

// Method names, as in the CSV and JSON.
namespace methods {
inline constexpr const char* kLgh = "lgh";
inline constexpr const char* kRtslc = "rtslc";             // stochastic lightcuts, the peer method (a grid of its own)
inline constexpr const char* kBruteForce = "brute_force";  // rasterized, all S0, unshadowed
inline constexpr const char* kBruteForceRatio = "brute_force_ratio";        // ... with the frame's shadow estimate
inline constexpr const char* kBruteForceShadowed = "brute_force_shadowed";  // one ray per light and pixel
inline constexpr const char* kUniform = "uniform";                          // M of the N lights, scaled by N / M
inline constexpr const char* kUniformShadowed = "uniform_shadowed";         // ... with exact visibility
inline constexpr const char* kUniformRatio = "uniform_ratio";  // about M fresh lights, the frame's shadow estimate
}  // namespace methods

// The pass name the shadowed brute force (BruteForcePass, not a frame pass) is recorded under.
inline constexpr const char* kBruteForceShadowedPass = "brute force shadowed";

struct Measurement {
  std::string method;  // methods::k*
  std::string series;  // grid, baseline, scaling
  RenderSettings settings;
  PointSpec point;
  size_t subsetLights = 0;  // uniform*: M
  size_t vplTarget = 0, vpls = 0,
         inputLights = 0;  // the VPLs asked for and made, |S0| (budget: settings.inputLights.vpls)
  std::map<std::string, std::vector<double>> passMs;      // per repeat
  std::vector<double> timeMs, timeUnshadowedMs, frameMs;  // per repeat: the compared times
  double buildMs = kNaN;                                  // the LGH's build, or the lightcuts' tree build
  bool extrapolated = false;
  LightStats lights;
  std::vector<double> rmseUnshadowed, psnrUnshadowed, rmseShadowed, psnrShadowed, maeShadowed;
  std::vector<double> rmseExactRatio;  // LGH: the irradiance with the reference's visibility ratio (the floor)
  double othersCpu = 0;  // the largest share of the machine other processes took during an accepted sample
  std::string image;     // .npy of the (shadowed) estimate, relative to the output folder

  bool lgh() const { return method == methods::kLgh; }
  bool lightcuts() const { return method == methods::kRtslc; }
  bool gridPoint() const { return lgh() || lightcuts(); }  // `point` says its settings
  void addPassTimes(const FrameStats& stats) {
    for (const gl::PassTiming& p : stats.passes) passMs[p.name].push_back(p.wallMs > 0 ? p.wallMs : p.gpuMs);
  }
  void addUnshadowedError(const ErrorStats& e) {
    rmseUnshadowed.push_back(e.rmse);
    psnrUnshadowed.push_back(e.psnr);
  }
  void addShadowedError(const ErrorStats& e) {
    rmseShadowed.push_back(e.rmse);
    psnrShadowed.push_back(e.psnr);
    maeShadowed.push_back(e.mae);
  }
  double passMedian(const std::string& pass) const {
    const auto it = passMs.find(pass);
    return it == passMs.end() ? kNaN : median(it->second);
  }
};

struct ReferenceInfo {
  size_t pixels = 0, imagePixels = 0;
  double fraction = 1, seconds = 0;
  std::uint64_t rays = 0, pairs = 0;
  unsigned threads = 0;
  bool cached = false;
  std::string cacheFile;
};

// One scene at one VPL target: the reference and every measurement against it.
struct Case {
  SceneSpec scene;
  bool scaling = false;  // the time-vs-VPL-count series: no reference, one VPL count per row
  size_t vplTarget = 0, vplBudget = 0, inputLights = 0, vpls = 0, emitterSamples = 0, pointLights = 0;
  int levels = 0;
  double clampDistance = 0;
  RenderSettings base;  // every measurement's settings differ from these only where it says
  std::vector<double> buildMs;
  std::vector<double> treeBuildMs;  // the lightcuts' light tree over S0 (when the grid has lightcut points)
  ReferenceInfo reference;
  std::vector<Measurement> measurements;
};

}  // namespace lgh::bench
