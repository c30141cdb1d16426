#pragma once
// The frame: one readable list of passes (Renderer::render), the targets they hand to each other,
// and the per-pass timings. lgh-render, lgh-viewer, the tests and the benchmarks all render
// through this class; there is no second implementation of a pass anywhere.

#include <string>
#include <vector>

#include "render/camera_view.h"
#include "render/gl/buffer.h"
#include "render/gl/profiler.h"
#include "render/image_io.h"
#include "render/passes/composite_pass.h"
#include "render/passes/direct_light_pass.h"
#include "render/passes/gbuffer_pass.h"
#include "render/settings.h"

namespace lgh {

// Images a frame can hand back (AOVs).
enum class Aov { Final, Direct, Emission, Albedo, Normal, Position };
Aov parseAov(const std::string& name);  // "final", "direct", "emission", "albedo", "normal", "position"
std::vector<std::string> aovNames();

struct FrameStats {
  std::vector<gl::PassTiming> passes;
  unsigned nonFinitePixels = 0;  // NaN/Inf pixels written black by the composite pass (should be 0)
  double totalMs() const;
};

// The scene camera named in settings; else the scene's first camera; else one framing the scene's bounds.
Camera resolveCamera(const Scene& scene, const RenderSettings& settings);

class Renderer {
 public:
  Renderer(const SceneGpu& scene, const RenderSettings& settings);

  const RenderSettings& settings() const { return settings_; }
  void setSettings(const RenderSettings& settings);  // reallocates targets when the size changes

  FrameStats render(const CameraView& view);
  ImageRGBA readImage(Aov aov) const;
  const GBuffer& gbuffer() const { return gbuffer_; }
  const gl::Texture2D& texture(Aov aov) const;
  float clampDistance() const;  // d_c in use (resolves the automatic default)

 private:
  void allocateTargets();
  void uploadFrameUniforms(const CameraView& view);

  const SceneGpu& scene_;
  RenderSettings settings_;
  gl::Profiler profiler_;
  gl::Buffer frameUniforms_;
  unsigned frameIndex_ = 0;

  // Passes, in frame order.
  GBufferPass gbufferPass_;
  DirectLightPass directPass_;
  CompositePass compositePass_;

  // Targets the passes hand to each other.
  GBuffer gbuffer_;
  gl::Texture2D direct_;
  gl::Texture2D final_;
};

}  // namespace lgh
