#pragma once
// The exact unshadowed sum over every input light at every pixel, in a compute shader: the reference
// the light pass is measured against (same G-buffer, same shading and clamp, no rasterization). Not a pass
// of the frame: render/exact/ holds what the benchmarks and tests check the frame with.
//   in:  BruteForceInputs: GBuffer (position, normal), S0 lights (and the scene's BVH when shadowed);
//        frame uniforms
//   out: irradiance (RGBA32F, rgb; a = 0)

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/passes/gbuffer_pass.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"

namespace lgh {

struct BruteForceInputs {
  const GBuffer& gbuffer;
  const gl::Buffer& lights;  // gpu::GpuLight, `lightCount` valid
  size_t lightCount = 0;
  // Shadowed: one shadow ray per light per pixel through this scene's BVH (exact shadowed reference).
  const SceneGpu* shadowedIn = nullptr;
};

class BruteForcePass {
 public:
  BruteForcePass();
  void execute(const BruteForceInputs& in, float clampDistance, gl::Texture2D& irradiance) const;

 private:
  static constexpr size_t kMaxLightsPerDispatch = 32768;  // see the constructor: llvmpipe's loop limit
  static constexpr size_t kMaxShadowedLightsPerDispatch = 32;
  gl::Program program_;
  mutable TracingProgram shadowed_;  // with one shadow ray per light (LGH_SHADOWED)
  size_t maxBlockLights_ = 0;
};

}  // namespace lgh
