#pragma once
// Every render parameter, declared once: name, default, range and help, grouped by the pass that
// reads it (each pass takes its group). The CLI (lgh-render), the viewer's panel and script, the
// sweep's --set and its CSV/JSON all walk this list with visitSettings(), so a parameter added here
// appears everywhere with the same name and limits. Limits that are the code's own come from its
// constants (shared/*.h), not retyped numbers.

#include <algorithm>
#include <string>

#include "shared/lgh_types.h"
#include "shared/light_pass_types.h"

namespace lgh {

// The image and how it is shown.
struct ImageSettings {
  int width = 640;
  int height = 360;
  std::string camera;     // scene camera name; empty: the scene's first camera, or frame its bounds
  float exposure = 0.0f;  // EV applied before tone mapping (display formats only)
  std::string toneMap = "aces";
};

// Input lights S0 (InputLightsPass); rebuilt only when one of these changes.
struct InputLightSettings {
  int vpls = 100000;  // VPL budget: ceil(vpls / bounces) light paths, up to `bounces` VPLs each
  int bounces = 2;
  int emitterSamples = 16384;  // points on emissive triangles, fed to the LGH as direct lights
  int maxDirectLights = 16;    // more punctual lights than this: point lights go to the LGH as S0
  int seed = 1;
  bool operator==(const InputLightSettings& o) const {
    return vpls == o.vpls && bounces == o.bounces && emitterSamples == o.emitterSamples &&
           maxDirectLights == o.maxDirectLights && seed == o.seed;
  }
  bool operator!=(const InputLightSettings& o) const { return !(*this == o); }
};

// The hierarchy (LghBuildPass).
struct HierarchySettings {
  int levels = 0;  // 0: automatic (the paper's rule)
};

// The light pass (LightVolumePass) and its interleaving (InterleavePass).
struct LightPassSettings {
  float alpha = 1.0f;         // R_l = alpha h_l
  int startLevel = 1;         // finest level blended: 1 (S1) or 0 (S0)
  int interleave = 1;         // n x n interleaved sampling
  bool overdraw = false;      // count fragments per pixel (AOV "overdraw")
  bool bruteForce = false;    // every S0 light at every pixel, weight 1 (exact unshadowed)
  bool volumeCulling = true;  // sphere-bounding rectangles depth-tested against the surfaces; false: the paper's cubes
};

// Indirect shadows: the light pass's selection of k lights per pixel and the shadow rays to them.
struct ShadowSettings {
  int samples = 4;          // k shadow rays per pixel; 0: indirect light unshadowed
  bool skipFinest = false;  // true: the finest level blended (S1, or S0 from start level 0) is not picked (the paper)
  bool uniform = false;     // pick lights uniformly instead of by contribution (for comparison)
  int targets = 8;  // input lights drawn per grid light each frame as ray targets (at least 2k); 0: jittered centres
  bool resampleTargets = true;    // each pixel picks among the drawn targets by what they add there
  bool weighTargets = true;       // weigh a sample by what its drawn targets add over what the centre adds
  bool blendTargets = true;       // blend each drawn target by its own distance, not its grid light's centre's
  bool countUnselectable = true;  // grid lights that reach a pixel but cannot be selected there add to T
  bool correctIrradiance = true;  // scale the indirect light by the samples' mean weight D, shrunk by its variance
  float correctionError = 0.1f;   // the LGH irradiance's expected relative error: the prior spread of D
  float correctionSampleSpread = 1.0f;  // the prior spread of one sample's D, pooled with the k samples' own
  float defensive = 0.0f;               // a grid light's selection importance adds this x its cosine-free contribution
  float spread = 1.0f;  // jitter of a cluster's shadow-ray target (targets = 0), in its standard deviations

  // Input lights drawn per grid light each frame: at least two per shadow sample. The m drawn lights are
  // shared by every pixel of the frame, and their mean factor is what a sample's weight (and so D) rests
  // on, an error the k samples do not average: m growing with k keeps more samples lowering the error
  // (Sponza 10K, k = 16, unfiltered: m = 16 0.171, m = 32 0.166). At most kMaxShadowTargets (2 x 16).
  int drawnTargets() const {
    return targets > 0 ? std::min(std::max(targets, 2 * samples), int(gpu::kMaxShadowTargets)) : 0;
  }

  // The defensive share the light pass and the shadow pass use: only samples weighed by their drawn
  // targets have heavy weights to bound (the paper's jittered centres are weighed by the centre alone).
  float selectionDefensive() const { return targets > 0 && weighTargets ? defensive : 0.0f; }

  // Whether the light pass counts what unselectable grid lights add (LGH_COUNT_UNSELECTABLE): only the
  // weighed samples' T estimates the input lights' sum, and only when every level is selected by
  // contribution is it that sum's (with the finest level skipped or uniform selection T is not).
  bool countsUnselectable() const {
    return countUnselectable && targets > 0 && weighTargets && !skipFinest && !uniform && samples > 0;
  }
};

// The a-trous filter over the shadow ratio (ShadowFilterPass).
struct ShadowFilterSettings {
  int passes = 5;  // 0: the raw ratio, unfiltered
  float normalPower = 64.0f;
  float planeSigma = 1.0f;   // tangent-plane distance in pixel footprints (x the step) at weight e^-1/2
  float ratioSigma = 0.25f;  // ratio difference at weight e^-1/2
};

// Temporal accumulation (AccumulationPass): while the camera is still (or moves a little) and the
// lights do not change, each frame's raw irradiance and shadow ratio are averaged with the earlier
// frames' (reprojected through the G-buffer), so the error keeps falling instead of staying at one
// frame's. With n x n interleaving the light-to-tile dealing rotates every frame so that n^2
// frames see every light at every pixel. Off by default, so that each render() is one frame as
// before (pinned frames, benchmarks); the viewer turns it on, and lgh-render with --frames > 1.
struct AccumulationSettings {
  bool enabled = false;
  int maxFrames = 1024;     // history length cap: beyond it the oldest frames fade out (moving average)
  float filterFade = 0.5f;  // a-trous ratio sigma x N^-filterFade and floor(filterFade log2 N) widest passes
                            // skipped for N accumulated frames (0: no fade)
};

struct RenderSettings {
  ImageSettings image;
  bool directShadows = true;   // DirectLightPass: one shadow ray per punctual light
  bool indirect = true;        // light through the LGH; false: emission and direct light only
  float clampDistance = 0.0f;  // d_c in metres; 0 = automatic (1e-2 of the scene diagonal)
  InputLightSettings inputLights;
  HierarchySettings hierarchy;
  LightPassSettings lightPass;
  ShadowSettings shadows;
  ShadowFilterSettings filter;
  AccumulationSettings accumulation;
};

struct SettingInfo {
  const char* name;  // also the CLI flag: --name
  const char* help;
  double min = 0, max = 0;  // inclusive range for numbers; min == max means unbounded
};

// visit(value&, SettingInfo) for each setting, in the order users see them.
template <typename Settings, typename Visitor>
void visitSettings(Settings& s, Visitor&& visit) {
  auto& image = s.image;
  visit(image.width, SettingInfo{"width", "image width in pixels", 1, 16384});
  visit(image.height, SettingInfo{"height", "image height in pixels", 1, 16384});
  visit(image.camera,
        SettingInfo{"camera",
                    "scene camera by name (default: the scene's first camera, else one framing the scene's bounds)"});
  visit(image.exposure, SettingInfo{"exposure", "exposure in EV for PNG/JPEG output", -20, 20});
  visit(image.toneMap, SettingInfo{"tonemap", "tone curve for PNG/JPEG output: clamp, reinhard, aces"});
  visit(s.directShadows, SettingInfo{"direct-shadows", "trace shadow rays for direct light"});
  visit(s.clampDistance,
        SettingInfo{"clamp-distance", "d_c: distances below it count as d_c in 1/d^2 (0 = 1e-2 x scene diagonal)", 0,
                    1e9});
  visit(s.indirect,
        SettingInfo{"indirect",
                    "light through the LGH (VPLs, emissive surfaces, many point lights); false: direct light only"});
  auto& lights = s.inputLights;
  visit(lights.vpls,
        SettingInfo{"vpls", "VPL budget: ceil(vpls / bounces) light paths of up to `bounces` VPLs", 0, 16000000});
  visit(lights.bounces, SettingInfo{"bounces", "diffuse bounces per light path (a VPL at each)", 1, 3});
  visit(lights.emitterSamples,
        SettingInfo{"emitter-samples", "points on emissive triangles fed to the LGH as direct lights", 0, 16000000});
  visit(
      lights.maxDirectLights,
      SettingInfo{"max-direct-lights",
                  "with more punctual lights than this, point lights go through the LGH instead of exact direct light",
                  0, 1000000});
  visit(lights.seed, SettingInfo{"seed", "random seed of the VPLs and emitter samples", 0, 2147483647});
  auto& pass = s.lightPass;
  visit(pass.alpha,
        SettingInfo{"alpha", "LGH blending radius R_l = alpha h_l: larger is more accurate and slower", 0.25, 16});
  visit(s.hierarchy.levels,
        SettingInfo{"levels", "LGH levels L (0 = automatic: largest L with |S1| < |S0| / 2)", 0, gpu::kMaxBuildLevels});
  visit(pass.startLevel,
        SettingInfo{"start-level", "finest level the light pass blends: 1 (S1) or 0 (the input lights)", 0, 1});
  visit(pass.interleave,
        SettingInfo{"interleave", "n x n interleaved sampling of the light pass (1, 2, 4)", 1, gpu::kMaxInterleave});
  visit(pass.overdraw, SettingInfo{"overdraw", "count fragments per pixel in the light pass (AOV overdraw, summary)"});
  visit(pass.volumeCulling,
        SettingInfo{"volume-culling",
                    "draw each light volume as its 2R sphere's screen rectangle, depth-tested so that surfaces behind "
                    "it are not shaded (false: the paper's cubes, every covered pixel shaded)"});
  visit(
      pass.bruteForce,
      SettingInfo{"brute-force", "shade every input light at every pixel with weight 1 (exact unshadowed sum; slow)"});
  auto& shadows = s.shadows;
  visit(shadows.samples, SettingInfo{"shadow-samples", "k: shadow rays per pixel for indirect light (0 = unshadowed)",
                                     0, gpu::kMaxShadowSamples});
  visit(shadows.skipFinest,
        SettingInfo{"shadow-skip-finest",
                    "do not pick lights of the finest level blended (S1, or S0 with start-level 0) for shadow rays"});
  visit(shadows.uniform, SettingInfo{"shadow-uniform", "pick shadow lights uniformly instead of by contribution"});
  visit(shadows.targets,
        SettingInfo{
            "shadow-targets",
            "input lights drawn per grid light each frame, by their share of its importance, as shadow-ray "
            "targets, at least twice shadow-samples of them (0: the paper's target, the cluster's centre jittered "
            "by its spread)",
            0, gpu::kMaxShadowTargets});
  visit(shadows.resampleTargets,
        SettingInfo{"shadow-resample-targets",
                    "each pixel picks among a grid light's drawn targets by their unshadowed contribution there "
                    "(false: by brightness alone, as drawn)"});
  visit(shadows.weighTargets,
        SettingInfo{"shadow-weigh-targets",
                    "weigh each shadow sample by what its grid light's drawn targets add at the pixel over what the "
                    "grid light's centre adds (the selection's weight), so the ratio converges to the exact one"});
  visit(shadows.blendTargets,
        SettingInfo{"shadow-blend-targets",
                    "blend each drawn target by its own distance to the pixel (false: by its grid light's centre's): "
                    "the levels' blending sums to 1 at every distance, so the weighed samples converge to the exact "
                    "ratio instead of one in which lights near a level's fade count twice or not at all"});
  visit(shadows.countUnselectable,
        SettingInfo{"shadow-count-unselectable",
                    "grid lights that reach a pixel but cannot be selected there (their centre in a level's fade-in "
                    "hole, behind the pixel's tangent plane or facing away) add what one of their drawn targets adds "
                    "to the samples' estimate of what the input lights add (no ray is spent on them), so that the "
                    "irradiance correction does not darken the image as it trusts that estimate"});
  visit(shadows.correctIrradiance,
        SettingInfo{"shadow-correct-irradiance",
                    "scale the shadowed indirect light by the weighed samples' filtered mean weight, an unbiased "
                    "estimate of what the input lights add over what the grid lights add, shrunk toward 1 as far as it "
                    "is uncertain (shadow-correction-lgh-error): the image converges to the exact shadowed irradiance "
                    "instead of the LGH's irradiance times the exact ratio"});
  visit(shadows.correctionError,
        SettingInfo{"shadow-correction-lgh-error",
                    "with shadow-correct-irradiance, the LGH irradiance's expected relative error f: the mean weight D "
                    "is trusted by f^2 / (f^2 + var D), so a noisy D (few samples, one frame) keeps the LGH's "
                    "irradiance and a certain one (many samples, taps or frames) converges to the exact one",
                    0.0, 10.0});
  visit(shadows.correctionSampleSpread,
        SettingInfo{"shadow-correction-sample-spread",
                    "with shadow-correct-irradiance, the prior spread (standard deviation) of one shadow sample's "
                    "mean weight, pooled as one sample's worth with the k samples' own spread to give D's variance "
                    "(with k = 1 it is the only estimate)",
                    0.0, 1e3});
  visit(shadows.defensive,
        SettingInfo{"shadow-defensive",
                    "defensive selection: a grid light's importance for shadow samples adds this times what it would "
                    "add without the cosines at the pixel and at the light, which bounds the weights of grid lights "
                    "whose centre grazes or faces away from the pixel while their input lights do not "
                    "(with shadow-weigh-targets and drawn targets)",
                    0.0, 100.0});
  visit(shadows.spread, SettingInfo{"shadow-spread",
                                    "jitter of a cluster's shadow-ray target with shadow-targets=0, in its standard "
                                    "deviations",
                                    0, 16});
  auto& filter = s.filter;
  visit(filter.passes, SettingInfo{"filter-passes", "a-trous passes over the shadow ratio (0 = raw ratio)", 0, 8});
  visit(filter.normalPower, SettingInfo{"filter-normal-power", "a-trous normal weight max(0, n.n')^p", 0, 1024});
  visit(filter.planeSigma,
        SettingInfo{"filter-plane-sigma", "a-trous tangent-plane distance weight, in pixel footprints", 0.01, 1000});
  visit(filter.ratioSigma, SettingInfo{"filter-ratio-sigma", "a-trous shadow-ratio difference weight", 0.001, 100});
  auto& accumulation = s.accumulation;
  visit(accumulation.enabled,
        SettingInfo{"accumulate",
                    "average the indirect light's raw estimates over frames while the camera and lights are still "
                    "(history reprojected through the G-buffer; interleaving rotated per frame; default on in the "
                    "viewer and in lgh-render with --frames > 1)"});
  visit(accumulation.maxFrames,
        SettingInfo{"accumulate-max-frames", "frames the history holds at most; older ones fade out", 1, 1 << 20});
  visit(
      accumulation.filterFade,
      SettingInfo{"accumulate-filter-fade",
                  "the a-trous ratio sigma shrinks as N^-fade with N accumulated frames, and floor(fade log2 N) of the "
                  "widest passes are skipped (0: filter as for one frame)",
                  0, 4});
}

// Sets the setting called `name` from text, checking its type and range (the viewer's `set`, the
// sweep's --set). Throws std::invalid_argument naming the setting and the problem, or listing the
// settings when there is none of that name.
void setSetting(RenderSettings& settings, const std::string& name, const std::string& value);
// "NAME=VALUE" form of setSetting.
void applySetting(RenderSettings& settings, const std::string& assignment);

}  // namespace lgh
