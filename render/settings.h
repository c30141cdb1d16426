#pragma once
// Every render parameter, declared once: name, default, range and help. The CLI (lgh-render), the
// viewer's UI and the sweep's CSV/JSON all walk this list with visitSettings(), so a parameter
// added here appears everywhere with the same name and limits.

#include <string>

namespace lgh {

struct RenderSettings {
  int width = 640;
  int height = 360;
  std::string camera;        // scene camera name; empty: the scene's first camera, or frame its bounds
  float exposure = 0.0f;     // EV applied before tone mapping (display formats only)
  std::string toneMap = "aces";
  bool directShadows = true;
  float clampDistance = 0.0f;  // d_c in metres; 0 = automatic (1e-2 of the scene diagonal)

  // Input lights S0 (rebuilt only when one of these changes).
  bool indirect = true;        // light through the LGH; false: emission and direct light only
  int vpls = 100000;           // VPL budget: ceil(vpls / bounces) light paths, up to `bounces` VPLs each
  int bounces = 2;
  int emitterSamples = 16384;  // points on emissive triangles, fed to the LGH as direct lights
  int maxDirectLights = 16;    // more punctual lights than this: point lights go to the LGH as S0
  int seed = 1;

  // The hierarchy and its light pass.
  float alpha = 1.0f;          // R_l = alpha h_l
  int levels = 0;              // 0: automatic (the paper's rule)
  int startLevel = 1;          // finest level blended: 1 (S1) or 0 (S0)
  int interleave = 1;          // n x n interleaved sampling
  bool overdraw = false;       // count fragments per pixel (AOV "overdraw")
  bool bruteForce = false;     // every S0 light at every pixel, weight 1 (exact unshadowed)

  // Indirect shadows.
  int shadowSamples = 4;       // k shadow rays per pixel; 0: indirect light unshadowed
  bool shadowSkipFinest = true;  // the finest level blended (S1) is not picked for shadow rays
  bool shadowUniform = false;  // pick lights uniformly instead of by contribution (for comparison)
  float shadowSpread = 1.0f;   // jitter of a cluster's shadow-ray target, in its standard deviations
  int filterPasses = 5;        // a-trous passes over the shadow ratio; 0: unfiltered
  float filterNormalPower = 64.0f;
  float filterPlaneSigma = 1.0f;
  float filterRatioSigma = 0.25f;
};

struct SettingInfo {
  const char* name;  // also the CLI flag: --name
  const char* help;
  double min = 0, max = 0;  // inclusive range for numbers; min == max means unbounded
};

// visit(value&, SettingInfo) for each setting, in the order users see them.
template <typename Settings, typename Visitor>
void visitSettings(Settings& s, Visitor&& visit) {
  visit(s.width, SettingInfo{"width", "image width in pixels", 1, 16384});
  visit(s.height, SettingInfo{"height", "image height in pixels", 1, 16384});
  visit(s.camera, SettingInfo{"camera", "scene camera by name (default: the scene's first camera, else one framing the scene's bounds)"});
  visit(s.exposure, SettingInfo{"exposure", "exposure in EV for PNG/JPEG output", -20, 20});
  visit(s.toneMap, SettingInfo{"tonemap", "tone curve for PNG/JPEG output: clamp, reinhard, aces"});
  visit(s.directShadows, SettingInfo{"direct-shadows", "trace shadow rays for direct light"});
  visit(s.clampDistance, SettingInfo{"clamp-distance", "d_c: distances below it count as d_c in 1/d^2 (0 = 1e-2 x scene diagonal)", 0, 1e9});
  visit(s.indirect, SettingInfo{"indirect", "light through the LGH (VPLs, emissive surfaces, many point lights); false: direct light only"});
  visit(s.vpls, SettingInfo{"vpls", "VPL budget: ceil(vpls / bounces) light paths of up to `bounces` VPLs", 0, 16000000});
  visit(s.bounces, SettingInfo{"bounces", "diffuse bounces per light path (a VPL at each)", 1, 3});
  visit(s.emitterSamples, SettingInfo{"emitter-samples", "points on emissive triangles fed to the LGH as direct lights", 0, 16000000});
  visit(s.maxDirectLights, SettingInfo{"max-direct-lights", "with more punctual lights than this, point lights go through the LGH instead of exact direct light", 0, 1000000});
  visit(s.seed, SettingInfo{"seed", "random seed of the VPLs and emitter samples", 0, 2147483647});
  visit(s.alpha, SettingInfo{"alpha", "LGH blending radius R_l = alpha h_l: larger is more accurate and slower", 0.25, 16});
  visit(s.levels, SettingInfo{"levels", "LGH levels L (0 = automatic: largest L with |S1| < |S0| / 2)", 0, 11});
  visit(s.startLevel, SettingInfo{"start-level", "finest level the light pass blends: 1 (S1) or 0 (the input lights)", 0, 1});
  visit(s.interleave, SettingInfo{"interleave", "n x n interleaved sampling of the light pass (1, 2, 4)", 1, 8});
  visit(s.overdraw, SettingInfo{"overdraw", "count fragments per pixel in the light pass (AOV overdraw, summary)"});
  visit(s.bruteForce, SettingInfo{"brute-force", "shade every input light at every pixel with weight 1 (exact unshadowed sum; slow)"});
  visit(s.shadowSamples, SettingInfo{"shadow-samples", "k: shadow rays per pixel for indirect light (0 = unshadowed)", 0, 16});
  visit(s.shadowSkipFinest, SettingInfo{"shadow-skip-finest", "do not pick lights of the finest level blended (S1) for shadow rays"});
  visit(s.shadowUniform, SettingInfo{"shadow-uniform", "pick shadow lights uniformly instead of by contribution"});
  visit(s.shadowSpread, SettingInfo{"shadow-spread", "jitter of a cluster's shadow-ray target, in its standard deviations", 0, 16});
  visit(s.filterPasses, SettingInfo{"filter-passes", "a-trous passes over the shadow ratio (0 = raw ratio)", 0, 8});
  visit(s.filterNormalPower, SettingInfo{"filter-normal-power", "a-trous normal weight max(0, n.n')^p", 0, 1024});
  visit(s.filterPlaneSigma, SettingInfo{"filter-plane-sigma", "a-trous tangent-plane distance weight, in pixel footprints", 0.01, 1000});
  visit(s.filterRatioSigma, SettingInfo{"filter-ratio-sigma", "a-trous shadow-ratio difference weight", 0.001, 100});
}

}  // namespace lgh
