#pragma once
// Indirect shadows (docs/design.md §5-§6), after the light pass has picked k lights per pixel:
//   ShadowRayPass:    GBuffer, ShadowSlots, lights, ShadowTargets, the light pass's irradiance -> raw
//                     visibility ratio (RGBA32F: r ratio, g rays, b the ratio's weight D)
//   ShadowFilterPass: raw ratio, unshadowed irradiance, GBuffer -> visibility factor (RGBA32F: r; the ratio
//                     times the filtered D when correcting the irradiance), by
//                     an a-trous filter applied as a ratio estimator; a ratio accumulated over N frames
//                     (N in the raw ratio's alpha) is filtered with its ratio sigma x N^-sigmaFade

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_volume_pass.h"
#include "render/passes/shadow_targets_pass.h"

namespace lgh {

class ShadowRayPass {
 public:
  ShadowRayPass();
  // `lightPass` is what the light pass that filled `slots` was run with (blending, selection mode and
  // spread, frame seed).
  void execute(const SceneGpu& scene, const GBuffer& gbuffer, const ShadowSlots& slots, const TileLayout& layout,
               const gl::Buffer& inputLights, const GpuHierarchy& hierarchy, const ShadowTargets& targets,
               const LightPassOptions& lightPass, const gl::Texture2D& lightPassIrradiance,
               gl::Texture2D& rawRatio) const;

 private:
  gl::Program program_;
};

// How the filter's output scales the LGH's irradiance by the shadow samples' mean weight D: by
// 1 + f^2 / (f^2 + var D) (D - 1), var D the filtered variance of the pixel's D.
struct IrradianceCorrection {
  bool enabled = false;
  float lghError = 0.0f;  // f: the LGH irradiance's expected relative error
};

class ShadowFilterPass {
 public:
  ShadowFilterPass();
  // With correction.enabled, r is the ratio times the filtered mean weight shrunk toward 1 by its variance
  // (ShadowSettings::correctIrradiance, correctionError).
  void execute(const GBuffer& gbuffer, const gl::Texture2D& rawRatio, const gl::Texture2D& irradiance,
               const ShadowFilterSettings& options, const IrradianceCorrection& correction,
               gl::Texture2D& filteredRatio, float sigmaFade = 0.0f);

 private:
  gl::Program program_;
  gl::Texture2D ping_, pong_;
};

}  // namespace lgh
