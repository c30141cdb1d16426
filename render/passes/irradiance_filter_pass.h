#pragma once
// The irradiance filter (glsl/irradiance_atrous.comp; docs/design.md §12): the shadow filter's a-trous
// kernel, passes, normal and plane weights over an irradiance that carries its own shadows (the
// stochastic lightcuts' estimate), with a relative luminance difference in place of the ratio's.
//   in:  the G-buffer, the irradiance (RGBA32F), the frames it holds
//   out: the filtered irradiance (RGBA32F; alpha kept)

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/gbuffer_pass.h"
#include "render/settings.h"

namespace lgh {

struct IrradianceFilterOptions {
  ShadowFilterSettings filter;  // passes, normal power, plane sigma; ratio sigma as the luminance sigma
  float sigmaFade = 0.0f;       // accumulating: AccumulationSettings::filterFade; else 0
  int frames = 1;               // the frames the irradiance holds
};

class IrradianceFilterPass {
 public:
  IrradianceFilterPass();
  // With 0 passes the output is a copy of the input.
  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  void execute(const GBuffer& gbuffer, const gl::Texture2D& irradiance, const IrradianceFilterOptions& options,
               gl::Texture2D& filtered);

 private:
  gl::Program program_;
  gl::UniformBlocks uniforms_;  // one gpu::IrradianceFilterUniforms per pass
  gl::Texture2D ping_, pong_;
};

}  // namespace lgh
