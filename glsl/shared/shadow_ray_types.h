// The shadow-ray pass's types, shared by its shaders (shadow_rays.comp, shadow_trace.comp,
// shadow_ratio.comp) and C++ (ShadowRayPass): its uniforms (one block, std140) and its queue of rays.
#ifndef LGH_SHADOW_RAY_TYPES_H
#define LGH_SHADOW_RAY_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// Scalars in groups of four (std140 and C++ agree without padding; see gpu_prelude.h).
GPU_STRUCT(ShadowRayUniforms) {
  uint samples;       // k
  uint tilesPerAxis;  // n: the slots and the light pass's irradiance are in its (tiled) layout
  uint tileWidth;
  uint tileHeight;

  uint races;            // m input lights drawn per grid light (ShadowTargets); 0: jittered centres
  uint selectFlags;      // kSelect* (light_pass_types.h): the selection the light pass made
  uint resampleTargets;  // 1: pick among a grid light's drawn lights by their geometric factor here
  uint weighTargets;     // 1: weigh a grid light's visibility by its drawn lights' G over its centre's

  float spread;         // jitter scale: the jitter's standard deviation is spread x the cluster's
  float defensive;      // the light pass's defensive share (ShadowEstimator::defensive)
  float sampleSpread;   // the prior spread of one sample's D (ShadowEstimator::correctionSampleSpread)
  float clampDistance;  // d_c

  // The blending of the light pass, to recompute a selected light's importance.
  float alpha;
  float topCellSize;
  uint firstLevel;
  uint levels;

  uint bruteForce;
  uint frameSeed;
  uint firstRow;  // the rows [firstRow, endRow) whose rays are queued now (the queue holds a batch of rows)
  uint endRow;
};
GPU_CHECK_OFFSET(ShadowRayUniforms, races, 16);
GPU_CHECK_OFFSET(ShadowRayUniforms, spread, 32);
GPU_CHECK_OFFSET(ShadowRayUniforms, alpha, 48);
GPU_CHECK_OFFSET(ShadowRayUniforms, bruteForce, 64);
GPU_CHECK_SIZE(ShadowRayUniforms, 80);

// The queue (one buffer): its counts, then the rays, a texel each. shadow_rays.comp appends a ray for each slot that
// needs one; shadow_trace.comp traces them, one an invocation, through an indirect dispatch of the groups
// counted here, so that SIMD lanes trace neighbouring rays and none waits on a slot without one.
GPU_STRUCT(ShadowRayQueueCounts) {
  uint rays;
  uint groupsX;  // ceil(rays / kShadowTraceGroupSize): glDispatchComputeIndirect's (x, y, z) from here
  uint groupsY;  // 1
  uint groupsZ;  // 1
};
GPU_CHECK_SIZE(ShadowRayQueueCounts, 16);
GPU_CONST uint kShadowTraceGroupSize = 64u;
GPU_CONST uint kShadowQueueDispatchOffset = 4u;  // bytes: where groupsX is

// A queued ray: from pixel slot `slot`'s surface (slot = (y W + x) k + j) towards `target`, stopping short
// of it; a blocked one zeroes the slot's weight. One texel: shadow_trace.comp makes the ray again from
// the G-buffer, as shadow_rays.comp made it (shadowRay), rather than read it: llvmpipe stores a texel
// one invocation at a time, and storing the origin and direction too (32 bytes a ray) left 10-20 ms
// more of the pass's other work at Sponza 640x360, k = 4.
GPU_STRUCT(QueuedShadowRay) {
  vec3 target;
  uint slot;
};
GPU_CHECK_SIZE(QueuedShadowRay, 16);

GPU_NAMESPACE_END
#endif
