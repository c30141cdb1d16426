#pragma once
// Every render parameter, declared once: name, default, range and help, grouped by the pass that
// reads it (each pass takes its group). The CLI (lgh-render), the viewer's panel and script, the
// sweep's --set and its CSV/JSON all walk this list with visitSettings(), so a parameter added here
// appears everywhere with the same name and limits. Limits that are the code's own come from its
// constants (shared/*.h), not retyped numbers.

#include <algorithm>
#include <iosfwd>
#include <string>
#include <vector>

#include "render/scene/bvh.h"
#include "shared/lgh_types.h"
#include "shared/light_pass_types.h"
#include "shared/light_tree_types.h"

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
  bool volumeCulling = true;  // depth-culled screen octagons of the 2R sphere (icosahedra when the sphere
                              // holds the camera); false: the paper's cubes
};

// Indirect shadows: the light pass's selection of k lights per pixel and the shadow rays to them. The
// user picks an estimator; the other fields are ablations of it (docs/settings.md). What a frame runs is
// these resolved by resolveShadowEstimator (render/shadow_estimator.h), the one place their gates live.
struct ShadowSettings {
  int samples = 4;                       // k shadow rays per pixel; 0: indirect light unshadowed
  std::string estimator = "converging";  // converging | paper | uniform (render/shadow_estimator.h)
  // Ablations of the converging (and uniform) estimator.
  int targets = 8;                // input lights drawn per grid light each frame (at least 2k); 0: jittered centres
  bool skipFinest = false;        // the finest level blended (S1, or S0 from start level 0) is not picked
  bool resampleTargets = true;    // each pixel picks among the drawn targets by what they add there
  bool weighTargets = true;       // weigh a sample by what its drawn targets add over what the centre adds
  bool blendTargets = true;       // blend each drawn target by its own distance, not its grid light's centre's
  bool countUnselectable = true;  // grid lights that reach a pixel but cannot be selected there add to T
  bool correctIrradiance = true;  // scale the indirect light by the samples' mean weight D, shrunk by its variance
  float correctionError = 0.1f;   // the LGH irradiance's expected relative error: the prior spread of D
  float correctionSampleSpread = 1.0f;  // the prior spread of one sample's D, pooled with the k samples' own
  float defensive = 0.0f;               // a grid light's selection importance adds this x its cosine-free contribution
  // Ablation of the paper's estimator (and of converging with targets = 0).
  float spread = 1.0f;  // jitter of a cluster's shadow-ray target, in its standard deviations
  // false: the rays are not traced (none blocked), so that the pass's other work can be timed alone.
  bool trace = true;
  // The most shadow rays queued at once (GPU memory, 16 bytes a ray; at least a row's): the rows whose
  // rays fit are queued and traced in turn.
  int queuedRays = 1 << 20;
};

// The a-trous filter over the shadow ratio (ShadowFilterPass).
struct ShadowFilterSettings {
  int passes = 5;  // 0: the raw ratio, unfiltered (with interleaving still resolved over the tiles)
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
// What the history does in a frame in which the lights or the geometry moved (docs/design.md §6,
// "history under motion"): restart it everywhere; keep the visibility ratio's and take this frame's
// irradiance (the LGH paper's choice); keep each pixel's as far as its temporal test finds the
// lighting there unchanged; or keep it all, whatever changed, as SVGF's temporal accumulation does (the
// lightcuts paper's choice; its length is maxFrames). In kHistoryMotionChoices' order (= gpu::kMotion* - 1).
enum class HistoryMotion { Restart, Ratio, Gradient, Keep };

struct AccumulationSettings {
  bool enabled = false;
  int maxFrames = 1024;     // history length cap: beyond it the oldest frames fade out (moving average)
  float filterFade = 0.5f;  // a-trous ratio sigma x N^-filterFade and floor(filterFade log2 N) widest passes
                            // skipped for N accumulated frames (0: no fade)
  HistoryMotion motion = HistoryMotion::Gradient;
  float motionTolerance = 0.1f;  // gradient: a relative change of the unshadowed irradiance that drops all history
};

// The peer method, real-time stochastic lightcuts (RtslcPass; docs/design.md §12): indirect light from the
// same S0 through a light tree instead of the LGH, shadowed sample by sample.
// How the lightcuts are denoised (docs/measurements.md, "The lightcuts' denoiser"): their shadowed
// irradiance by SVGF's variance-guided filter, or in ratio form, the same samples' unshadowed sum by it and
// their visibility ratio by the LGH's shadow filter, multiplied. In kRtslcDenoiserChoices' order.
enum class RtslcDenoiser { Shadowed, Ratio };

struct RtslcSettings {
  int samples = 8;            // n: light samples (and shadow rays) per pixel: a cut of n m^2 nodes (the paper's spp)
  int blockSize = 8;          // B: pixels per side of the blocks that share a cut (1: per-pixel cuts)
  int interleave = 1;         // m: an m x m group of pixels splits each cut of n m^2 nodes (1, 2, 4)
  float errorLimit = 0.001f;  // the cut's distance floor, as a share of the lights' box diagonal
  // The denoiser (IrradianceFilterPass; its passes are ShadowFilterSettings::passes), tuned on the lightcuts
  // (docs/measurements.md, "The lightcuts' denoiser"): SVGF's luminance stop sigma_l in standard deviations,
  // and the a-trous normal power and plane sigma (the shadow filter's normal power 64 stopped the lightcuts'
  // blur on Sponza's columns and arches, where their noise needs it: filtered / raw 0.29 against 0.17).
  float filterSigma = 16.0f;
  float filterNormalPower = 4.0f;
  float filterPlaneSigma = 1.0f;
  RtslcDenoiser denoiser = RtslcDenoiser::Shadowed;
};

// How the indirect light is made: not at all (emission and direct light only), through the LGH, or by the
// peer method, real-time stochastic lightcuts (docs/design.md §12). In kIndirectMethodChoices' order.
enum class IndirectMethod { None, Lgh, Rtslc };

struct RenderSettings {
  ImageSettings image;
  IndirectMethod indirectMethod = IndirectMethod::Lgh;
  bool directShadows = true;   // DirectLightPass: one shadow ray per punctual light
  float clampDistance = 0.0f;  // d_c in metres; 0 = automatic (1e-2 of the scene diagonal)
  float gpuMemoryLimit = 0;    // MB the engine's GL objects may hold; 0: the device's reported free memory
  BvhLayout bvhLayout = BvhLayout::Compressed8;  // the BVH the rays traverse, built when the scene loads (SceneGpu)
  InputLightSettings inputLights;
  HierarchySettings hierarchy;
  LightPassSettings lightPass;
  ShadowSettings shadows;
  ShadowFilterSettings filter;
  AccumulationSettings accumulation;
  RtslcSettings rtslc;

  bool indirect() const { return indirectMethod != IndirectMethod::None; }
};

// Who a setting is for. User: shown by --help, the README and the viewer panel's main section.
// Advanced: --help-all and the panel's collapsed section. Ablation: an experiment on the estimator
// (docs/settings.md), set with --set NAME=VALUE, recorded in sweep CSVs, listed by --help-all only.
enum class SettingTier { User, Advanced, Ablation };

struct SettingInfo {
  const char* name;         // also the CLI flag: --name
  const char* help;         // one line; the why is in docs/design.md
  double min = 0, max = 0;  // inclusive range for numbers; min == max means unbounded
  SettingTier tier = SettingTier::Advanced;
  // Changing it keeps the accumulated history: it does not change the frames' raw estimates (how the
  // image is shown, the filter, which runs on the accumulated values every frame, the camera, whose moves
  // are reprojected, and what is applied to the history's sums).
  bool keepsHistory = false;
  const char* choices = nullptr;  // text settings with a fixed set of values: "a|b|c"

  SettingInfo forUsers() const {
    return with([](SettingInfo& i) { i.tier = SettingTier::User; });
  }
  SettingInfo ablation() const {
    return with([](SettingInfo& i) { i.tier = SettingTier::Ablation; });
  }
  SettingInfo keepingHistory() const {
    return with([](SettingInfo& i) { i.keepsHistory = true; });
  }
  SettingInfo oneOf(const char* values) const {
    return with([&](SettingInfo& i) { i.choices = values; });
  }

 private:
  template <typename Change>
  SettingInfo with(Change&& change) const {
    SettingInfo copy = *this;
    change(copy);
    return copy;
  }
};

// The estimator names (render/shadow_estimator.h) and tone curves, as SettingInfo::choices.
inline constexpr const char* kShadowEstimatorChoices = "converging|paper|uniform";
inline constexpr const char* kToneMapChoices = "aces|reinhard|clamp";
inline constexpr const char* kIndirectMethodChoices = "none|lgh|rtslc";
inline constexpr const char* kRtslcDenoiserChoices = "shadowed|ratio";
inline constexpr const char* kHistoryMotionChoices = "restart|ratio|gradient|keep";

// visit(value&, SettingInfo) for each setting, in the order users see them.
template <typename Settings, typename Visitor>
void visitSettings(Settings& s, Visitor&& visit) {
  auto& image = s.image;
  visit(image.width, SettingInfo{"width", "image width in pixels", 1, 16384}.forUsers());
  visit(image.height, SettingInfo{"height", "image height in pixels", 1, 16384}.forUsers());
  visit(image.camera, SettingInfo{"camera", "scene camera by name (default: the first, else one framing the scene)"}
                          .forUsers()
                          .keepingHistory());
  visit(image.exposure,
        SettingInfo{"exposure", "exposure in EV for PNG/JPEG output", -20, 20}.forUsers().keepingHistory());
  visit(image.toneMap,
        SettingInfo{"tonemap", "tone curve for PNG/JPEG output"}.oneOf(kToneMapChoices).keepingHistory());
  visit(s.directShadows, SettingInfo{"direct-shadows", "trace shadow rays for direct light"});
  visit(s.clampDistance,
        SettingInfo{"clamp-distance", "d_c in 1/max(d^2, d_c^2), metres (0: 1e-2 x scene diagonal)", 0, 1e9});
  visit(s.gpuMemoryLimit,
        SettingInfo{"gpu-memory-limit",
                    "MB the GPU buffers and textures may hold (0: the free memory the device reports)", 0, 1e9}
            .keepingHistory());
  visit(s.bvhLayout,
        SettingInfo{"bvh", "node layout of the BVH the rays traverse (when the scene loads)"}.oneOf(kBvhLayoutChoices));
  visit(s.indirectMethod, SettingInfo{"indirect-method",
                                      "lgh (the lighting grid hierarchy), rtslc (stochastic lightcuts, the peer), none"}
                              .forUsers()
                              .oneOf(kIndirectMethodChoices));
  auto& lights = s.inputLights;
  visit(lights.vpls, SettingInfo{"vpls", "VPL budget (ceil(vpls / bounces) light paths)", 0, 16000000}.forUsers());
  visit(lights.bounces, SettingInfo{"bounces", "diffuse bounces per light path, a VPL at each", 1, 3});
  visit(lights.emitterSamples,
        SettingInfo{"emitter-samples", "points on emissive triangles fed to the LGH as lights", 0, 16000000});
  visit(lights.maxDirectLights,
        SettingInfo{"max-direct-lights", "beyond this many punctual lights, point lights go through the LGH", 0,
                    1000000});
  visit(lights.seed, SettingInfo{"seed", "random seed of the VPLs and emitter samples", 0, 2147483647});
  auto& pass = s.lightPass;
  visit(
      pass.alpha,
      SettingInfo{"alpha", "blending radius R_l = alpha h_l: larger is more accurate and slower", 0.25, 16}.forUsers());
  visit(s.hierarchy.levels, SettingInfo{"levels", "LGH levels (0: the paper's rule, largest L with |S1| < |S0| / 2)", 0,
                                        gpu::kMaxBuildLevels});
  visit(pass.startLevel, SettingInfo{"start-level", "finest level blended: 1 (S1) or 0 (the input lights)", 0, 1});
  visit(pass.interleave,
        SettingInfo{"interleave", "n x n interleaved sampling of the light pass (1, 2, 4)", 1, gpu::kMaxInterleave}
            .forUsers());
  visit(pass.overdraw,
        SettingInfo{"overdraw", "count the light pass's fragments per pixel (AOV overdraw)"}.keepingHistory());
  visit(pass.volumeCulling,
        SettingInfo{"volume-culling",
                    "depth-culled octagons and icosahedra as light volumes (false: the paper's cubes)"});
  visit(pass.bruteForce,
        SettingInfo{"brute-force", "every input light at every pixel (the exact unshadowed sum; slow)"});
  auto& shadows = s.shadows;
  visit(shadows.samples, SettingInfo{"shadow-samples", "k: shadow rays per pixel for indirect light (0: unshadowed)", 0,
                                     gpu::kMaxShadowSamples}
                             .forUsers());
  visit(shadows.estimator,
        SettingInfo{"shadow-estimator", "converging (the default), paper (Lin & Yuksel) or uniform selection"}
            .forUsers()
            .oneOf(kShadowEstimatorChoices));
  visit(shadows.targets,
        SettingInfo{"shadow-targets", "input lights drawn per grid light as ray targets, at least 2k (0: centres)", 0,
                    gpu::kMaxShadowTargets}
            .ablation());
  visit(shadows.skipFinest,
        SettingInfo{"shadow-skip-finest", "the finest level blended is not selected for shadow rays"}.ablation());
  visit(
      shadows.resampleTargets,
      SettingInfo{"shadow-resample-targets", "pick among the drawn targets by what they add at the pixel"}.ablation());
  visit(shadows.weighTargets,
        SettingInfo{"shadow-weigh-targets", "weigh samples by what the drawn targets add over the centre"}.ablation());
  visit(shadows.blendTargets,
        SettingInfo{"shadow-blend-targets", "blend each drawn target by its own distance"}.ablation());
  visit(shadows.countUnselectable,
        SettingInfo{"shadow-count-unselectable", "count what unselectable grid lights add to T"}.ablation());
  visit(shadows.correctIrradiance,
        SettingInfo{"shadow-correct-irradiance", "correct the LGH irradiance by the samples' mean weight D"}
            .ablation()
            .keepingHistory());
  visit(shadows.correctionError,
        SettingInfo{"shadow-correction-lgh-error", "f: the LGH's expected relative error, D's prior spread", 0.0, 10.0}
            .ablation()
            .keepingHistory());
  visit(shadows.correctionSampleSpread,
        SettingInfo{"shadow-correction-sample-spread", "prior spread of one sample's D", 0.0, 1e3}.ablation());
  visit(
      shadows.defensive,
      SettingInfo{"shadow-defensive", "share of the cosine-free contribution in the selection", 0.0, 100.0}.ablation());
  visit(
      shadows.spread,
      SettingInfo{"shadow-spread", "jitter of the paper's cluster targets, in standard deviations", 0, 16}.ablation());
  visit(shadows.trace,
        SettingInfo{"shadow-trace", "trace the shadow rays (false: none blocked; times the pass's other work)"}
            .ablation());
  visit(shadows.queuedRays,
        SettingInfo{"shadow-queued-rays", "most shadow rays queued at once (16 bytes each; rows traced in turn)", 1,
                    65535 * 64}
            .keepingHistory());
  auto& filter = s.filter;
  visit(
      filter.passes,
      SettingInfo{"filter-passes", "a-trous passes over the shadow ratio (0: raw)", 0, 8}.forUsers().keepingHistory());
  visit(filter.normalPower,
        SettingInfo{"filter-normal-power", "a-trous normal weight max(0, n.n')^p", 0, 1024}.keepingHistory());
  visit(filter.planeSigma,
        SettingInfo{"filter-plane-sigma", "a-trous plane-distance sigma, in pixel footprints", 0.01, 1000}
            .keepingHistory());
  visit(filter.ratioSigma,
        SettingInfo{"filter-ratio-sigma", "a-trous ratio-difference sigma", 0.001, 100}.keepingHistory());
  auto& rtslc = s.rtslc;
  visit(rtslc.samples, SettingInfo{"rtslc-samples", "lightcuts: light samples per pixel n (a cut of n m^2 <= 32 nodes)",
                                   1, gpu::kMaxCutNodes});
  visit(rtslc.blockSize, SettingInfo{"rtslc-block", "lightcuts: pixels per side sharing a cut (1: per pixel)", 1, 64});
  visit(rtslc.interleave,
        SettingInfo{"rtslc-interleave", "lightcuts: m x m pixels split each cut's nodes (1, 2, 4; divides the block)",
                    1, 4});
  visit(rtslc.errorLimit,
        SettingInfo{"rtslc-error-limit", "lightcuts: the cut's distance floor, share of the lights' extent", 0, 1});
  visit(rtslc.denoiser,
        SettingInfo{"rtslc-denoiser", "lightcuts: filter the shadowed irradiance, or its ratio to the unshadowed apart"}
            .oneOf(kRtslcDenoiserChoices));
  visit(rtslc.filterSigma, SettingInfo{"rtslc-filter-sigma",
                                       "lightcuts' denoiser: luminance stop in standard deviations (SVGF)", 0.01, 1000}
                               .keepingHistory());
  visit(rtslc.filterNormalPower,
        SettingInfo{"rtslc-filter-normal-power", "lightcuts' denoiser: normal weight max(0, n.n')^p", 0, 1024}
            .keepingHistory());
  visit(rtslc.filterPlaneSigma,
        SettingInfo{"rtslc-filter-plane-sigma", "lightcuts' denoiser: plane-distance sigma, in pixel footprints", 0.01,
                    1000}
            .keepingHistory());
  auto& accumulation = s.accumulation;
  visit(accumulation.enabled,
        SettingInfo{"accumulate", "average frames while the view is still (on in the viewer and with --frames > 1)"}
            .forUsers());
  visit(accumulation.maxFrames,
        SettingInfo{"accumulate-max-frames", "frames the history holds at most", 1, 1 << 20}.keepingHistory());
  visit(accumulation.filterFade,
        SettingInfo{"accumulate-filter-fade", "ratio sigma x N^-fade over N frames, widest passes skipped", 0, 4}
            .keepingHistory());
  visit(
      accumulation.motion,
      SettingInfo{"accumulate-motion", "history when lights or meshes move: restart, keep the ratio's, test, keep all"}
          .oneOf(kHistoryMotionChoices)
          .keepingHistory());
  visit(accumulation.motionTolerance,
        SettingInfo{"accumulate-motion-tolerance", "gradient: relative irradiance change that drops a pixel's history",
                    1e-3, 10}
            .keepingHistory());
}

// Sets the setting called `name` from text, checking its type and range (the viewer's `set`, the
// sweep's --set). Throws std::invalid_argument naming the setting and the problem, or listing the
// settings when there is none of that name.
void setSetting(RenderSettings& settings, const std::string& name, const std::string& value);
// "NAME=VALUE" form of setSetting.
void applySetting(RenderSettings& settings, const std::string& assignment);
// The setting called `name` (its help, range, tier, choices); throws std::invalid_argument when there is none.
SettingInfo settingInfo(const std::string& name);
// SettingInfo::choices ("a|b|c") as a list, and whether `value` is one of them.
std::vector<std::string> choiceList(const char* choices);
bool isChoice(const char* choices, const std::string& value);
// An enum setting holds the index of its value in its SettingInfo::choices: its value as text, and back
// (the value must be one of the choices).
template <typename Enum>
std::string choiceName(Enum value, const char* choices) {
  return choiceList(choices).at(size_t(value));
}
template <typename Enum>
Enum choiceValue(const std::string& name, const char* choices) {
  const std::vector<std::string> list = choiceList(choices);
  return Enum(std::find(list.begin(), list.end(), name) - list.begin());
}
// The method's choice name (lgh, rtslc, none): what settings keys, CSVs and messages print.
std::ostream& operator<<(std::ostream& out, IndirectMethod method);
std::ostream& operator<<(std::ostream& out, RtslcDenoiser denoiser);
std::ostream& operator<<(std::ostream& out, HistoryMotion motion);
std::ostream& operator<<(std::ostream& out, BvhLayout layout);

}  // namespace lgh
