#pragma once
// Indirect shadows (DESIGN 5-6), after the light pass has picked k lights per pixel:
//   ShadowRayPass:    GBuffer, ShadowSlots, lights -> raw visibility ratio (RGBA32F: r ratio, g rays)
//   ShadowFilterPass: raw ratio, unshadowed irradiance, GBuffer -> filtered ratio (RGBA32F: r), by
//                     an a-trous filter applied as a ratio estimator

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_volume_pass.h"

namespace lgh {

struct ShadowRayOptions {
  float spread = 1.0f;  // jitter inside a cluster: its standard deviation is spread x the cluster's
  unsigned frameSeed = 0;
};

class ShadowRayPass {
 public:
  ShadowRayPass();
  // `lightPass` is what the light pass that filled `slots` was run with (selection mode, blending).
  void execute(const SceneGpu& scene, const GBuffer& gbuffer, const ShadowSlots& slots, const TileLayout& layout,
               const gl::Buffer& inputLights, const GpuHierarchy& hierarchy, const LightPassOptions& lightPass,
               const ShadowRayOptions& options, gl::Texture2D& rawRatio) const;

 private:
  gl::Program program_;
};

struct ShadowFilterOptions {
  int passes = 5;              // 0: the raw ratio, unfiltered
  float normalPower = 64.0f;
  float planeSigma = 1.0f;     // tangent-plane distance in pixel footprints (x the step) at weight e^-1/2
  float ratioSigma = 0.25f;    // ratio difference at weight e^-1/2
};

class ShadowFilterPass {
 public:
  ShadowFilterPass();
  void execute(const GBuffer& gbuffer, const gl::Texture2D& rawRatio, const gl::Texture2D& irradiance,
               const ShadowFilterOptions& options, gl::Texture2D& filteredRatio);

 private:
  gl::Program program_;
  gl::Texture2D ping_, pong_;
};

}  // namespace lgh
