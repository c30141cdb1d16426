#pragma once
// Final image: emission + direct + albedo / pi x indirect irradiance (unshadowed) x visibility ratio.
//   in:  CompositeInputs: GBuffer (emission, albedo), direct, indirect irradiance, visibility ratio
//   out: CompositeTargets: final radiance (RGBA32F), indirect radiance unshadowed (RGBA32F, an AOV);
//        returns the count of non-finite pixels (written black)

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/passes/gbuffer_pass.h"

namespace lgh {

struct CompositeInputs {
  const GBuffer& gbuffer;
  const gl::Texture2D& direct;
  const gl::Texture2D* indirectIrradiance = nullptr;  // null: no indirect light
  const gl::Texture2D* visibility = nullptr;          // null: visibility 1
};

struct CompositeTargets {
  gl::Texture2D& indirect;  // albedo / pi x irradiance, unshadowed
  gl::Texture2D& final;
};

class CompositePass {
 public:
  CompositePass();
  // Returns the number of pixels that were NaN or Inf before being written black.
  unsigned execute(const CompositeInputs& in, const CompositeTargets& out);

 private:
  gl::Program program_;
  gl::Texture2D black_, white_;
  gl::Buffer counter_;
};

}  // namespace lgh
