#pragma once
// Final image: emission + direct + albedo / pi x indirect irradiance (unshadowed) x visibility ratio.
//   in:  GBuffer (emission, albedo), direct, indirect irradiance, visibility ratio
//   out: final radiance (RGBA32F), indirect radiance unshadowed (RGBA32F, an AOV); count of
//        non-finite pixels (written black)

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/passes/gbuffer_pass.h"

namespace lgh {

class CompositePass {
 public:
  CompositePass();
  // indirect / visibility may be null: no indirect light, visibility 1.
  // Returns the number of pixels that were NaN or Inf before being written black.
  unsigned execute(const GBuffer& gbuffer, const gl::Texture2D& direct, const gl::Texture2D* indirectIrradiance,
                   const gl::Texture2D* visibility, gl::Texture2D& indirectOut, gl::Texture2D& out);

 private:
  gl::Program program_;
  gl::Texture2D black_, white_;
  gl::Buffer counter_;
};

}  // namespace lgh
