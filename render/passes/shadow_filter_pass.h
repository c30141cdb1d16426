#pragma once
// The shadow filter (docs/design.md §6): an a-trous filter over the raw visibility ratio, applied as a
// ratio estimator with the ratio's weights T (glsl/atrous.comp); a ratio accumulated over N frames
// (N in the raw ratio's alpha) is filtered with its ratio sigma x N^-sigmaFade.
//   in:  ShadowFilterInputs: the G-buffer, the raw ratio and the sampled irradiance (ShadowRayPass, or
//        accumulated)
// With interleaving, the sums are first resolved over the interleaving window, as the irradiance is.
//   out: visibility factor, RGBA32F: r the filtered ratio (times the filtered mean weight D, shrunk toward 1
//        by its variance, when correcting the irradiance), g the filtered ratio, b the mean weight

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/settings.h"

namespace lgh {

struct ShadowFilterInputs {
  const GBuffer& gbuffer;
  const gl::Texture2D& rawRatio;  // r ratio, g T's variance, b T, a frames
  // r: the luminance C of the (unshadowed) irradiance the samples' T were drawn against, which the filtered
  // mean weight D = sum T / sum C compares them with (with interleaving the tiles', not the resolved one)
  const gl::Texture2D& sampledIrradiance;
};

// How the filter's output scales the LGH's irradiance by the shadow samples' mean weight D: by
// 1 + f^2 / (f^2 + var D) (D - 1), var D the filtered variance of the pixel's D.
struct IrradianceCorrection {
  bool enabled = false;
  float lghError = 0.0f;  // f: the LGH irradiance's expected relative error
};

struct ShadowFilterOptions {
  ShadowFilterSettings filter;
  IrradianceCorrection correction;  // from the resolved ShadowEstimator
  float sigmaFade = 0.0f;           // accumulating: AccumulationSettings::filterFade; else 0
  // n x n interleaving of the light pass the samples come from: their sums are first resolved over the
  // window the irradiance was resolved with (1: none)
  int tilesPerAxis = 1;
  InterleaveFilter resolve = kInterleaveResolve;
};

class ShadowFilterPass {
 public:
  ShadowFilterPass();
  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  void execute(const ShadowFilterInputs& in, const ShadowFilterOptions& options, gl::Texture2D& visibility);

 private:
  gl::Program program_;
  gl::UniformBlocks uniforms_;  // one gpu::ShadowFilterUniforms per dispatch
  gl::Texture2D ping_, pong_;
};

}  // namespace lgh
