#pragma once
// Real-time stochastic lightcuts (Lin & Yuksel 2020; glsl/rtslc.comp, docs/design.md §12), the peer
// method of the LGH, over the same input lights, rays and light shading:
//   in:  RtslcInputs: SceneGpu (BVH), GBuffer, S0 and its light tree (LightTreePass)
//   out: RtslcTargets: the shadowed irradiance estimate (unbiased; with m x m interleaving, over m^2 frames)
// Two steps, timed apart: the cuts (one per block) and the sampling (n lights per pixel, one shadow ray
// each), which reads the last cuts.

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/light_tree_pass.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"
#include "render/settings.h"

namespace lgh {

struct RtslcInputs {
  const SceneGpu& scene;
  const GBuffer& gbuffer;
  const gl::Buffer& inputLights;  // S0 (gpu::GpuLight), `inputLightCount` valid: bound in one storage block
  size_t inputLightCount = 0;
  const GpuLightTree& tree;
};

struct RtslcOptions {
  RtslcSettings settings;
  float clampDistance = 0;  // d_c, as the LGH's
  unsigned frameSeed = 0;
};

struct RtslcTargets {
  gl::Texture2D& shadowed;  // RGBA32F
  // The ratio form's, written when set (all three or none): the same samples' unshadowed sum (RGBA32F), the
  // raw ratio as ShadowFilterInputs reads it (RGBA32F), the unshadowed luminance (R32F).
  gl::Texture2D* unshadowed = nullptr;
  gl::Texture2D* ratio = nullptr;
  gl::Texture2D* sampledLuminance = nullptr;
};

class RtslcPass {
 public:
  RtslcPass();
  // Both throw std::invalid_argument for settings out of range (samples, block size, interleave; samples x
  // interleave^2 cut nodes at most gpu::kMaxCutNodes, the block a multiple of the interleave).
  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  void selectCuts(const RtslcInputs& in, const RtslcOptions& options);
  void sample(const RtslcInputs& in, const RtslcOptions& options, const RtslcTargets& out);
  // The last cuts: gpu::kMaxCutNodes node indices per block, row by row from the bottom (kNoCutNode: unused).
  const gl::Buffer& cuts() const { return cuts_; }

 private:
  void bind(const RtslcInputs& in, const RtslcOptions& options, size_t dispatch, bool ratioOutputs);
  TracingProgram program_;
  gl::UniformBlocks uniforms_;  // the dispatch's gpu::RtslcUniforms, uploaded before each
  gl::Buffer cuts_;             // gpu::kMaxCutNodes node indices per block
};

}  // namespace lgh
