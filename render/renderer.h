#pragma once
// The frame: one readable list of passes (Renderer::render), the targets they hand to each other,
// and the per-pass timings. lgh-render, lgh-viewer, the tests and the benchmarks all render
// through this class; there is no second implementation of a pass anywhere.

#include <set>
#include <string>
#include <vector>

#include "render/aov.h"
#include "render/camera_view.h"
#include "render/gl/buffer.h"
#include "render/gl/profiler.h"
#include "render/image_io.h"
#include "render/light_builds.h"
#include "render/pass_names.h"
#include "render/passes/accumulation_pass.h"
#include "render/passes/composite_pass.h"
#include "render/passes/direct_light_pass.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/input_lights_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/irradiance_filter_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_tree_pass.h"
#include "render/passes/light_volume_pass.h"
#include "render/passes/rtslc_pass.h"
#include "render/passes/shadow_filter_pass.h"
#include "render/passes/shadow_ray_pass.h"
#include "render/passes/shadow_targets_pass.h"
#include "render/settings.h"

namespace lgh {

// What the LGH part of the frame drew, in device-independent counts.
struct LightStats {
  size_t inputLights = 0, pointLights = 0, emitterSamples = 0, vpls = 0;  // S0 and its parts
  int levels = 0;                                                         // L of the hierarchy in use
  std::vector<size_t> lightsPerLevel;  // lights drawn by the light pass: [0] S0, [l] level l
  // Per pixel of the image, only with settings.overdraw: fragments rasterized (the paper's Fig. 5
  // overdraw), fragments that shaded (non-zero blending weight), and the largest rasterized count.
  double rasterizedPerPixel = 0, shadedPerPixel = 0;
  unsigned maxRasterized = 0;
  // Shaded / rasterized: the share of the light pass's fragment work that adds light (0 if none ran).
  double efficiency() const { return rasterizedPerPixel > 0 ? shadedPerPixel / rasterizedPerPixel : 0.0; }
};

struct FrameStats {
  std::vector<gl::PassTiming> passes;
  LightStats lights;
  bool lightsRebuilt = false;    // S0 and the hierarchy were (re)built this frame
  unsigned nonFinitePixels = 0;  // NaN/Inf pixels written black by the composite pass (should be 0)
  // Frames in the accumulated indirect estimate of the pixels that stayed in view: frames since the
  // camera, the lights or the estimate's settings last changed, at most accumulation.maxFrames
  // (pixels that came into view since hold fewer); 0 without accumulation.
  int accumulatedFrames = 0;
  double totalMs() const;
  double passMs(const std::string& name) const;  // 0 when the pass did not run
};

// The scene camera named in settings; else the scene's first camera; else one framing the scene's bounds.
Camera resolveCamera(const Scene& scene, const RenderSettings& settings);

class Renderer {
 public:
  Renderer(const SceneGpu& scene, const RenderSettings& settings);

  const RenderSettings& settings() const { return settings_; }
  // The targets follow at the next render(): what the new settings switch off is freed there.
  void setSettings(const RenderSettings& settings);

  FrameStats render(const CameraView& view);
  // The next frame starts the accumulated history anew (render() does so itself when the lights or
  // the settings that the estimate depends on change).
  void restartAccumulation();
  // The frames' random sequence (shadow picks, interleave rotation, lightcut descents) from its start:
  // what follows no longer depends on the frames rendered before (lgh-bench sweep restarts it per point,
  // so that a point measures the same on any MPI rank).
  void restartRandomSequence() { frameIndex_ = 0; }
  ImageRGBA readImage(Aov aov) const;
  const GBuffer& gbuffer() const { return gbuffer_; }
  // An AOV this configuration does not render (the ratio unshadowed, the overdraw without counting) reads
  // as its neutral value: visibility 1, light and counts 0.
  const gl::Texture2D& texture(Aov aov) const;
  float clampDistance() const;           // d_c in use (resolves the automatic default)
  LghBuildOptions buildOptions() const;  // how the hierarchy is built (levels, smallest top cell)
  // The input lights and hierarchy in use (built by the first render()).
  const InputLights& inputLights() const { return inputLights_; }
  const GpuHierarchy& hierarchy() const { return hierarchy_; }
  const ShadowSlots& shadowSlots() const { return shadowSlots_; }  // the last frame's selection
  const GpuLightTree& lightTree() const { return lightTree_; }     // with --indirect-method rtslc

 private:
  // What the settings switch on, which decides the targets the frame holds and what its passes keep.
  struct Configuration {
    int width = 0, height = 0, interleave = 1;
    bool lgh = false, hierarchy = false, shadowed = false, lightcuts = false;
    bool overdraw = false, accumulating = false;
    bool operator==(const Configuration& o) const;
    bool operator!=(const Configuration& o) const { return !(*this == o); }
  };
  Configuration configuration() const;
  // Allocates the targets `configured_` uses and frees the rest, with what the passes and the light
  // builds hold for a method or feature that is off: the frame holds only what it uses.
  void allocateTargets();
  void releaseUnused();
  void uploadFrameUniforms(const CameraView& view);
  bool pointLightsThroughLgh() const;
  bool shadowed() const { return settings_.shadows.samples > 0; }
  // The indirect light through the stochastic lightcuts instead of the LGH (settings.indirectMethod).
  bool lightcuts() const;
  // Shadow rays aim at input lights drawn from the selected grid lights' clusters.
  bool drawsShadowTargets() const { return shadowEstimator_.drawnTargets > 0 && hierarchy_.gridLightCount > 0; }
  // This frame's shadow estimator (the settings resolved against its limits); says once on stderr what a
  // limit switched off.
  void resolveShadows();
  bool interleaved() const { return settings_.lightPass.interleave > 1; }
  bool accumulating() const { return settings_.indirect && settings_.accumulation.enabled; }
  // Restarts the history when the lights were rebuilt or the estimate's settings changed, and counts
  // the frames it holds while the camera is still.
  int updateAccumulation(bool lightsRebuilt, const CameraView& view);
  // Each pass's settings group: the user's settings with what this frame resolves.
  LightPassOptions lightPassOptions() const;
  // What the shadow rays read of the light pass that filled the slots (`lightPass`), to recompute its selection.
  static ShadowRayOptions shadowRayOptions(const LightPassOptions& lightPass);
  ShadowFilterOptions shadowFilterOptions() const;
  RtslcOptions rtslcOptions() const;
  LightPassTarget lightPassTarget();
  // The frame's steps that are more than one call: S0 and the hierarchy when they are out of date,
  // then the light pass with its optional interleaving.
  bool updateLights();
  LightPassDraws shadeIndirect(const LightPassOptions& options);
  LightStats lightStats(const LightPassDraws& draws) const;
  void measureOverdraw(LightStats& stats) const;
  // Runs `pass` inside a profiler scope called `name` (a passes:: constant).
  template <typename Pass>
  void timed(const char* name, Pass&& pass) {
    gl::Profiler::Scope scope(profiler_, name);
    pass();
  }

  const SceneGpu& scene_;
  RenderSettings settings_;
  Configuration configured_;  // what the targets were allocated for
  gl::Profiler profiler_;
  gl::Buffer frameUniforms_;
  unsigned frameIndex_ = 0;

  // Passes, in frame order.
  GBufferPass gbufferPass_;
  DirectLightPass directPass_;
  InputLightsPass inputLightsPass_;
  LghBuildPass buildPass_;
  InterleavePass interleavePass_;
  LightVolumePass lightPass_;
  ShadowTargetsPass shadowTargetsPass_;
  ShadowRayPass shadowRayPass_;
  AccumulationPass accumulationPass_;
  ShadowFilterPass shadowFilterPass_;
  LightTreePass lightTreePass_;  // the lightcuts' passes, in place of the LGH's
  RtslcPass rtslcPass_;
  IrradianceFilterPass irradianceFilterPass_;
  CompositePass compositePass_;

  ShadowEstimator shadowEstimator_;       // resolved each frame by resolveShadows()
  std::set<std::string> reportedLimits_;  // what a limit switched off, said once

  // What the accumulated history was summed with (settings as text) and where it was seen from.
  std::string accumulationKey_;
  CameraView accumulationView_;
  int accumulatedFrames_ = 0;

  // Built when the lights or their settings change, not every frame (LightBuilds decides).
  LightBuilds builds_;
  InputLights inputLights_;
  GpuHierarchy hierarchy_;
  GpuLightTree lightTree_;

  // Targets the passes hand to each other.
  GBuffer gbuffer_;
  gl::Texture2D direct_;
  Tiles tiles_;                       // interleaved surfaces and light-pass targets (n > 1)
  gl::Texture2D irradiance_;          // LGH irradiance, full resolution
  gl::Texture2D fragmentCounts_;      // R32UI, light-pass fragments per pixel (settings.overdraw)
  ShadowSlots shadowSlots_;           // k selected lights per light-pass pixel
  ShadowTargets shadowTargets_;       // input lights drawn per grid light as the rays' targets
  gl::Texture2D rawRatio_;            // r: visibility ratio from the shadow rays (accumulated; a: frames)
  gl::Texture2D sampledIrradiance_;   // R32F: the irradiance luminance the shadow samples were drawn against
  gl::Texture2D visibility_;          // r: filtered ratio
  gl::Texture2D filteredIrradiance_;  // the lightcuts' irradiance, filtered
  gl::Texture2D indirect_;            // albedo / pi x irradiance, unshadowed
  gl::Texture2D final_;
  const gl::Texture2D& target(Aov aov) const;  // empty where not rendered
  mutable gl::Texture2D neutralAov_;           // texture() of an AOV not rendered, made when asked for
};

}  // namespace lgh
