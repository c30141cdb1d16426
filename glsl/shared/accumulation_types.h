// Uniforms of the accumulation pass (one block per dispatch, std140), shared by accumulate.comp and C++
// (AccumulationPass).
#ifndef LGH_ACCUMULATION_TYPES_H
#define LGH_ACCUMULATION_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kAccumulateSums = 0u;               // stage 0: sums and outputs
GPU_CONST uint kAccumulateResolveIncomplete = 1u;  // stage 1: resolve of incomplete interleaved sums

// What moved since the last frame, and what the history does about it (HistoryMotion + 1).
GPU_CONST uint kMotionNone = 0u;      // nothing: the sums grow exactly
GPU_CONST uint kMotionRatio = 2u;     // the irradiance's history replaced by this frame's, the ratio's kept
GPU_CONST uint kMotionGradient = 3u;  // each pixel's history kept as far as its temporal tests allow
GPU_CONST uint kMotionKeep = 4u;      // the history kept whatever changed (SVGF), its length maxFrames

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

  float normalPower;      // stage 1: neighbour weight max(0, n.n')^normalPower
  float planeSigma;       // stage 1: tangent-plane distance in pixel footprints at weight e^-1/2
  uint motion;            // kMotion*
  float motionTolerance;  // kMotionGradient: the relative irradiance change that drops all history

  uint irradianceWhole;  // the frame's irradiance is its lights' exact sum (the LGH without interleaving)
  uint pad0, pad1, pad2;
};
GPU_CHECK_OFFSET(AccumulationUniforms, previousCameraPosition, 64);
GPU_CHECK_OFFSET(AccumulationUniforms, maxFrames, 76);
GPU_CHECK_OFFSET(AccumulationUniforms, stage, 80);
GPU_CHECK_OFFSET(AccumulationUniforms, tileWidth, 96);
GPU_CHECK_OFFSET(AccumulationUniforms, normalPower, 112);
GPU_CHECK_SIZE(AccumulationUniforms, 144);

GPU_NAMESPACE_END
#endif
