#pragma once
// The frame's indirect light, by one of two methods behind one interface (docs/design.md, "The frame"): the
// lighting grid hierarchy (LghIndirect) or the peer method, real-time stochastic lightcuts (RtslcIndirect).
// The Renderer chooses once per configuration (settings.indirectMethod) and calls the chosen method's steps
// in frame order around what the methods share (S0, the accumulation, the composite):
//   structure  what the method draws from S0, rebuilt when S0 or its own settings changed (the hierarchy,
//              the light tree; LightBuilds decides)
//   estimate   this frame's raw estimate: the irradiance, and the LGH's raw visibility ratio beside it
//   (the accumulation sums the raw estimate into the history, in the method's targets)
//   filter     the estimate denoised: the irradiance the composite multiplies by the albedo, and the
//              visibility that multiplies it where the method has one
// A method owns its passes, its targets and the options it builds for them from the settings.

#include "render/aov.h"
#include "render/camera_view.h"
#include "render/gl/profiler.h"
#include "render/light_builds.h"
#include "render/passes/accumulation_pass.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/input_lights_pass.h"
#include "render/scene/scene_gpu.h"
#include "render/settings.h"

namespace lgh {

// What the indirect part of a frame drew, in device-independent counts.
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

// What a frame hands its indirect method: the settings, the surfaces and S0, and the profiler its passes
// are timed by (under the names of render/pass_names.h).
struct IndirectFrame {
  const SceneGpu& scene;
  const RenderSettings& settings;
  const GBuffer& gbuffer;
  const InputLights& lights;  // S0
  float clampDistance = 0;    // d_c, resolved
  unsigned frameIndex = 0;    // the random sequence's frame: seeds, the interleaving's rotation
  bool accumulating = false;  // the accumulation runs on the raw estimate this frame
  gl::Profiler& profiler;

  unsigned frameSeed() const { return frameIndex * 0x9e3779b9u + unsigned(settings.inputLights.seed); }
  // Runs `pass` inside a profiler scope called `name` (a passes:: constant).
  template <typename Pass>
  void timed(const char* name, Pass&& pass) const {
    gl::Profiler::Scope scope(profiler, name);
    pass();
  }
};

// The raw estimate as the accumulation reads it, and the method's targets it accumulates into in place.
struct AccumulationSource {
  const gl::Texture2D& rawIrradiance;
  TileLayout layout;      // tiled when interleaving splits the surfaces
  int shadowSamples = 0;  // the ratio target holds this frame's raw ratio (0: the luminance's moments go there)
  AccumulationTargets targets;
  bool wholeIrradiance = false;  // the raw irradiance is its lights' exact sum, the same every still frame
};

// What the composite reads.
struct IndirectImage {
  const gl::Texture2D* irradiance = nullptr;  // before the albedo
  const gl::Texture2D* visibility = nullptr;  // r multiplies the irradiance; null: 1 (already shadowed)
};

class IndirectLight {
 public:
  virtual ~IndirectLight() = default;
  // The targets for `settings` (size, interleaving, shadowed or not, overdraw, accumulation), the old set
  // freed first; the frames read the rest of their settings from IndirectFrame.
  virtual void allocate(const RenderSettings& settings) = 0;
  // Frees every target, the structure and what the passes hold (the method is off); `builds` records it.
  virtual void release(LightBuilds& builds) = 0;
  // Builds the structure over S0 when LightBuilds says it is out of date; true when it did.
  virtual bool updateStructure(const IndirectFrame& frame, const InputLightKey& lights, LightBuilds& builds) = 0;
  virtual LightStats estimate(const IndirectFrame& frame) = 0;
  virtual AccumulationSource accumulation(const IndirectFrame& frame) = 0;
  virtual IndirectImage filter(const IndirectFrame& frame) = 0;
  // Counts read back after the frame's timings (the light pass's overdraw); nothing by default.
  virtual void countWork(LightStats&) const {}
  // The AOV's target where this method renders it (irradiance, ratio, visibility, overdraw); null otherwise.
  virtual const gl::Texture2D* target(Aov aov) const = 0;
};

}  // namespace lgh
