#include "render/exact/brute_force_pass.h"

#include <algorithm>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/lgh_types.h"

namespace lgh {

BruteForcePass::BruteForcePass()
    : program_(gl::Program::compute("brute_force.comp")), shadowed_("brute_force.comp", {{"LGH_SHADOWED", "1"}}) {
  // llvmpipe ends a shader invocation's loops after 65,535 iterations in total (gallivm's loop
  // limiter, one counter for all loops of the invocation), which silently dropped every light past
  // the 65,535th: keep each dispatch's loop iterations under it.
  maxBlockLights_ = std::min(gl::storageBlockElements(sizeof(gpu::GpuLight)), kMaxLightsPerDispatch);
}

void BruteForcePass::execute(const BruteForceInputs& in, float clampDistance, gl::Texture2D& irradiance) const {
  const gl::Program& program = in.shadowedIn ? shadowed_(*in.shadowedIn) : program_;
  if (in.shadowedIn) in.shadowedIn->bindForCompute();
  irradiance.clear(glm::vec4(0.0f));
  in.gbuffer.bindForReading();
  irradiance.bindImage(LGH_IMAGE_BRUTE_FORCE_IRRADIANCE, GL_READ_WRITE);
  program.set("clampDistance", clampDistance);
  // One storage block at a time; the shader adds each chunk's sum into the image.
  // Shadowed, every light's BVH traversal counts against the limit too (up to ~1,000 iterations).
  const size_t perDispatch = in.shadowedIn ? kMaxShadowedLightsPerDispatch : maxBlockLights_;
  for (size_t first = 0; first < in.lightCount; first += perDispatch) {
    const size_t n = std::min(perDispatch, in.lightCount - first);
    in.lights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, first * sizeof(gpu::GpuLight),
                        n * sizeof(gpu::GpuLight));
    program.set("lightCount", unsigned(n));
    program.dispatch2D(in.gbuffer.width, in.gbuffer.height, {8, 8});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  gl::checkErrors("brute-force pass");
}

}  // namespace lgh
