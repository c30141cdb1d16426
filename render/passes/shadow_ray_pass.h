#pragma once
// Shadow rays (docs/design.md §5), after the light pass has picked k lights per pixel: one ray per filled
// slot from the pixel's surface to the light (to one of a grid light's drawn input lights, or to its
// jittered centre), any-hit through the scene's BVH, each weighed by what its light adds over the
// importance the light pass selected it by. Three steps: glsl/shadow_rays.comp weighs the slots and
// queues their rays, shadow_trace.comp traces the queue (only rays, so that no SIMD lane idles on an
// empty slot), shadow_ratio.comp sums each pixel's visible weights. The queue holds a batch of rows'
// rays at a time (ShadowRayOptions::queuedRays), so its memory does not grow with the image.
//   in:  ShadowRayInputs: the scene's BVH, the G-buffer, the input lights S0 and the hierarchy, this
//        frame's drawn targets, the shadow slots and the light pass's irradiance (both in its layout)
//   out: ShadowRayTargets, full resolution: the raw visibility ratio (RGBA32F: r the ratio sum w V / sum w,
//        g the variance of T, b T, the samples' estimate of what the input lights add and the ratio's
//        weight, a 1) and the sampled irradiance (R32F: the luminance C of the light pass's irradiance T
//        is compared with; with interleaving the pixel's own tile's, unresolved)

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_volume_pass.h"
#include "render/passes/shadow_targets_pass.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"
#include "render/shadow_estimator.h"

namespace lgh {

struct ShadowRayInputs {
  const SceneGpu& scene;  // the BVH the rays traverse
  const GBuffer& gbuffer;
  const gl::Buffer& inputLights;  // S0 (gpu::GpuLight), `inputLightCount` valid: read as texels
  size_t inputLightCount = 0;
  const GpuHierarchy& hierarchy;
  const ShadowTargets& targets;              // this frame's drawn input lights per grid light (races 0: none)
  const ShadowSlots& slots;                  // the light pass's k selected lights per pixel, in `layout`
  TileLayout layout;                         // the light pass's (tiled) layout
  const gl::Texture2D& lightPassIrradiance;  // in `layout`
};

// What the rays read of the light pass that filled the slots (it must have run with the same values, to
// recompute each selected light's importance as it did), and the resolved estimator.
struct ShadowRayOptions {
  ShadowEstimator shadows;
  float alpha = 1.0f;          // R_l = alpha h_l
  int startLevel = 1;          // finest level blended
  bool bruteForce = false;     // every light weight 1
  float clampDistance = 0.0f;  // d_c, resolved
  unsigned frameSeed = 0;
  bool trace = true;  // false: no ray is traced (none blocked), to time the pass's other work alone
  // The most rays queued at once (at least a row's, W x k): the rows whose rays fit are queued and
  // traced in turn.
  size_t queuedRays = size_t(1) << 20;
};

struct ShadowRayTargets {
  gl::Texture2D& rawRatio;           // RGBA32F
  gl::Texture2D& sampledIrradiance;  // R32F
  // The rays traced, recorded (lgh-bench rays), or nullptr: a gpu::GpuRay per slot of every pixel, slot j of
  // pixel (x, y) at (j H + y) W + x, tMax 0 where none was traced; at least W x H x k of them.
  gl::Buffer* recordedRays = nullptr;
};

class ShadowRayPass {
 public:
  ShadowRayPass();
  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  void execute(const ShadowRayInputs& in, const ShadowRayOptions& options, const ShadowRayTargets& out);

 private:
  gl::Program sampling_;   // shadow_rays.comp: weighs the slots, queues the rays
  gl::Program recording_;  // the same, recording the rays (out.recordedRays)
  TracingProgram trace_;   // shadow_trace.comp
  gl::Program ratio_;      // shadow_ratio.comp
  gl::Buffer queue_;       // gpu::ShadowRayQueueCounts, then the queued gpu::QueuedShadowRay
  gl::BufferTexture queueTexels_;
  gl::Buffer slotWeights_;  // float per slot, at (y W + x) k + j
  // The input lights read as integer texels (a slot's resampling reads eight: through SSBOs, llvmpipe's
  // scalar word loads made them most of the pass's work besides the rays).
  gl::BufferTexture inputLightTexels_;
  gl::UniformBlocks uniforms_;  // one gpu::ShadowRayUniforms
};

}  // namespace lgh
