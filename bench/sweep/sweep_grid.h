#pragma once
// What lgh-bench sweep measures: the scenes (PATH@CAMERA) and the grid of LGH points, with the labels
// a point goes by in tables and file names.

#include <filesystem>
#include <string>
#include <vector>

#include "render/settings.h"

namespace lgh::bench {

// One point of the grid: the settings a sweep varies (the rest are the case's base settings). An LGH point,
// or with `lightcuts` a point of the stochastic lightcuts (--indirect-method rtslc), whose k is its samples
// per pixel n, interleave its m x m and `block` its cut-sharing block (alpha and start level unused).
struct PointSpec {
  float alpha = 1.0f;
  int startLevel = 1, interleave = 1, k = 4;
  bool filter = true;  // the a-trous filter over the shadow ratio (the lightcuts: over the irradiance); off: raw
  int frames = 1;      // still frames accumulated (settings.accumulation); the last one is measured
  bool lightcuts = false;
  int block = 8;
  bool operator<(const PointSpec& o) const;
  bool operator==(const PointSpec& o) const { return !(*this < o) && !(o < *this); }
  // `base` with this point's settings.
  RenderSettings applied(const RenderSettings& base) const;
};

// Every combination, start level slowest.
std::vector<PointSpec> grid(const std::vector<float>& alphas, const std::vector<int>& starts,
                            const std::vector<int>& ns, const std::vector<int>& ks, const std::vector<bool>& filters,
                            const std::vector<int>& frames = {1});
// The published sweep (docs/measurements.md): alpha x start level x interleaving (1, 4), without shadows (k = 0) and
// with k = 4 and the filter; then one parameter at a time around the defaults (alpha 1, S1, 1x1, k 4).
std::vector<PointSpec> readmePoints();
// The lightcuts' grid: samples n x block B x interleave m x filter x frames, but for the combinations the
// method does not take (n m^2 > 32 cut nodes, B not a multiple of m).
std::vector<PointSpec> lightcutPoints(const std::vector<int>& samples, const std::vector<int>& blocks,
                                      const std::vector<int>& interleaves, const std::vector<bool>& filters,
                                      const std::vector<int>& frames);

// "a=1 S1 4x4 k=4" (lightcuts: "n=8 B8 2x2"), " raw" without the filter, " 16 frames"
std::string settingsLabel(const PointSpec& p);
// "a1_s1_n4_k4_filter" (lightcuts: "rtslc_n8_b8_m2_filter"), "_f16" for 16 frames
std::string fileLabel(const PointSpec& p);

struct SceneSpec {
  std::filesystem::path path;
  std::string camera;  // empty: the scene's first camera
  std::string name;    // file stem, for tables and file names
};
// PATH or PATH@CAMERA (a path that exists as given wins over the split); throws if there is no such file.
SceneSpec parseSceneSpec(const std::string& text);

}  // namespace lgh::bench
