#pragma once
// Final image: emission + direct + indirect_unshadowed x visibility ratio.
//   in:  GBuffer (emission), direct, indirect (unshadowed), visibility ratio
//   out: final radiance (RGBA32F); count of non-finite pixels (written black)

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/passes/gbuffer_pass.h"

namespace lgh {

class CompositePass {
 public:
  CompositePass();
  // indirect / visibility may be null: no indirect light, visibility 1.
  // Returns the number of pixels that were NaN or Inf before being written black.
  unsigned execute(const GBuffer& gbuffer, const gl::Texture2D& direct, const gl::Texture2D* indirect,
                   const gl::Texture2D* visibility, gl::Texture2D& out);

 private:
  gl::Program program_;
  gl::Texture2D black_, white_;
  gl::Buffer counter_;
};

}  // namespace lgh
