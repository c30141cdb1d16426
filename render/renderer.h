#pragma once
// The frame: one readable list of passes (Renderer::render), the targets they hand to each other,
// and the per-pass timings. lgh-render, lgh-viewer, the tests and the benchmarks all render
// through this class; there is no second implementation of a pass anywhere.

#include <string>
#include <vector>

#include "render/aov.h"
#include "render/camera_view.h"
#include "render/gl/buffer.h"
#include "render/gl/profiler.h"
#include "render/image_io.h"
#include "render/indirect/indirect_light.h"
#include "render/indirect/lgh_indirect.h"
#include "render/indirect/rtslc_indirect.h"
#include "render/light_builds.h"
#include "render/pass_names.h"
#include "render/passes/accumulation_pass.h"
#include "render/passes/composite_pass.h"
#include "render/passes/direct_light_pass.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/input_lights_pass.h"
#include "render/settings.h"

namespace lgh {

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
  // The input lights and the structures over them (built by the first render() that draws them).
  const InputLights& inputLights() const { return inputLights_; }
  const GpuHierarchy& hierarchy() const { return lgh_.hierarchy(); }
  const ShadowSlots& shadowSlots() const { return lgh_.shadowSlots(); }  // the LGH's last selection
  // The LGH's shadow rays recorded into `rays` from the next frame on, until called with nullptr
  // (lgh-bench rays traces a frame's own; ShadowRayTargets::recordedRays says how they are laid out).
  void recordShadowRays(gl::Buffer* rays) { lgh_.recordShadowRays(rays); }
  const GpuLightTree& lightTree() const { return rtslc_.lightTree(); }  // with indirect-method rtslc

 private:
  // What the settings switch on, which decides the targets the frame holds and what its passes keep.
  struct Configuration {
    int width = 0, height = 0, interleave = 1;
    IndirectMethod method = IndirectMethod::None;
    RtslcDenoiser rtslcDenoiser = RtslcDenoiser::Shadowed;  // the ratio form has targets of its own
    bool shadowed = false, overdraw = false, accumulating = false;
    bool operator==(const Configuration& o) const;
    bool operator!=(const Configuration& o) const { return !(*this == o); }
  };
  Configuration configuration() const;
  // Chooses the indirect method for `configured_` and allocates the targets it uses; what is off (the
  // other method, S0 without indirect light, the history) is freed: the frame holds only what it uses.
  void allocateTargets();
  void uploadFrameUniforms(const CameraView& view);
  // The scene's point lights go into S0 (too many for exact direct light).
  bool pointLightsInS0() const;
  bool accumulating() const { return method_ && settings_.accumulation.enabled; }
  IndirectFrame indirectFrame();
  // S0 when its settings or the lights changed, and the method's structure over it when out of date.
  bool updateLights(const IndirectFrame& frame);
  // What the history is to do with this frame (updateAccumulation).
  struct HistoryUpdate {
    int stillFrames = 0;       // the frames it holds while the camera and the lights are still, this one included
    bool lightsMoved = false;  // rebuilt lights with the same settings: each pixel's test keeps or drops its history
  };
  // Restarts the history when the estimate's settings changed (or the lights were rebuilt and motion
  // restarts it), says whether the lights moved, and counts the still frames.
  HistoryUpdate updateAccumulation(bool lightsRebuilt, const CameraView& view);
  // The method's raw estimate summed into its history, the accumulated estimate in its place.
  void accumulate(const IndirectFrame& frame, const CameraView& view, bool lightsMoved);
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
  unsigned geometryVersion_ = 0;  // SceneGpu::geometryVersion() of the last frame

  // Passes, in frame order; the indirect methods (render/indirect/) hold theirs.
  GBufferPass gbufferPass_;
  DirectLightPass directPass_;
  InputLightsPass inputLightsPass_;
  AccumulationPass accumulationPass_;
  CompositePass compositePass_;
  LghIndirect lgh_;
  RtslcIndirect rtslc_;
  IndirectLight* method_ = nullptr;  // the configured one; null without indirect light

  // What the accumulated history was summed with (settings as text) and where it was seen from.
  std::string accumulationKey_;
  CameraView accumulationView_;
  int accumulatedFrames_ = 0;

  // Built when the lights or their settings change, not every frame (LightBuilds decides).
  LightBuilds builds_;
  InputLights inputLights_;

  // Targets the frame's own passes hand to each other.
  GBuffer gbuffer_;
  gl::Texture2D direct_;
  gl::Texture2D indirect_;  // albedo / pi x irradiance (the LGH's unshadowed)
  gl::Texture2D final_;
  const gl::Texture2D* target(Aov aov) const;  // null where not rendered
  mutable gl::Texture2D neutralAov_;           // texture() of an AOV not rendered, made when asked for
};

}  // namespace lgh
