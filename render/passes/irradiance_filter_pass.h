#pragma once
// The lightcuts' variance-guided filter (glsl/irradiance_atrous.comp; docs/design.md §12): SVGF's
// a-trous passes (Schied et al. 2017), as the lightcuts' paper filters, over an irradiance that carries its
// own shadows: the m x m interleaving resolved, each pixel's luminance variance estimated (spatially, or
// from the accumulation's temporal moments), and the luminance stop scaled by its standard deviation. The
// kernel is the shadow filter's; its normal and plane weights are tuned for the lightcuts (RtslcSettings).
//   in:  the G-buffer, the irradiance (RGBA32F), the accumulation's moments when accumulating
//   out: the filtered irradiance (RGBA32F; alpha: its variance, what the last pass stopped on)

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/gbuffer_pass.h"
#include "render/settings.h"

namespace lgh {

struct IrradianceFilterOptions {
  int passes = 5;           // ShadowFilterSettings::passes (0: the resolve and the variance only)
  RtslcSettings lightcuts;  // the interleave m and the filter's sigma_l, normal power and plane sigma
  float sigmaFade = 0.0f;   // accumulating: AccumulationSettings::filterFade; else 0
  // Accumulating: the accumulation's ratio image (g: the accumulated mean's luminance variance, a: N frames);
  // nullptr: one frame.
  const gl::Texture2D* moments = nullptr;
};

class IrradianceFilterPass {
 public:
  // From this many accumulated frames a pixel's variance is the temporal one (SVGF's 4).
  static constexpr unsigned kMinTemporalFrames = 4;
  IrradianceFilterPass();
  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  // With 0 passes the output is the resolved irradiance with its variance estimate in alpha.
  void execute(const GBuffer& gbuffer, const gl::Texture2D& irradiance, const IrradianceFilterOptions& options,
               gl::Texture2D& filtered);

 private:
  gl::Program program_;
  gl::UniformBlocks uniforms_;  // one gpu::IrradianceFilterUniforms per dispatch
  gl::Texture2D ping_, pong_;
};

}  // namespace lgh
