// Uniforms of the accumulation pass (one block per dispatch, std140), shared by accumulate.comp and C++
// (AccumulationPass).
#ifndef LGH_ACCUMULATION_TYPES_H
#define LGH_ACCUMULATION_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kAccumulateSums = 0u;               // stage 0: sums and outputs
GPU_CONST uint kAccumulateResolveIncomplete = 1u;  // stage 1: resolve of incomplete interleaved sums

// A vec3 followed by a scalar, scalars in groups of four (see gpu_prelude.h).
GPU_STRUCT(AccumulationUniforms) {
  mat4 previousViewProjection;  // camera-relative: clip = M (p - previousCameraPosition)
  vec3 previousCameraPosition;
  float maxFrames;  // history length cap

  uint stage;          // kAccumulate*
  uint hasHistory;     // 0: restart (every pixel's history is empty)
  uint shadowSamples;  // k: the ratio image holds this frame's raw ratio from k samples (0: unshadowed)
  uint tilesPerAxis;   // n

  uint tileWidth;
  uint tileHeight;
  float planeTolerance;   // tangent-plane distance, in pixel footprints, still the same surface
  float normalTolerance;  // smallest n . n' still the same surface

  float normalPower;  // stage 1: neighbour weight max(0, n.n')^normalPower
  float planeSigma;   // stage 1: tangent-plane distance in pixel footprints at weight e^-1/2
  uint pad0, pad1;
};
GPU_CHECK_OFFSET(AccumulationUniforms, previousCameraPosition, 64);
GPU_CHECK_OFFSET(AccumulationUniforms, maxFrames, 76);
GPU_CHECK_OFFSET(AccumulationUniforms, stage, 80);
GPU_CHECK_OFFSET(AccumulationUniforms, tileWidth, 96);
GPU_CHECK_OFFSET(AccumulationUniforms, normalPower, 112);
GPU_CHECK_SIZE(AccumulationUniforms, 128);

GPU_NAMESPACE_END
#endif
