// Uniforms of the shadow filter (atrous.comp; one block per dispatch, std140), shared with C++
// (ShadowFilterPass).
#ifndef LGH_SHADOW_FILTER_TYPES_H
#define LGH_SHADOW_FILTER_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kFilterPrepare = 0u;  // stage 0: (raw ratio, sampled irradiance) -> (S, U D, U, var(U D))
GPU_CONST uint kFilterPass = 1u;     // stage 1: one a-trous pass with holes of stepSize
GPU_CONST uint kFilterFinish = 2u;   // stage 2: -> visibility factor
GPU_CONST uint kFilterResolve = 3u;  // with interleaving, after stage 0: the interleaving window's sums

// Scalars in groups of four (see gpu_prelude.h).
GPU_STRUCT(ShadowFilterUniforms) {
  uint stage;              // kFilter*
  int stepSize;            // stage 1: the holes between taps
  int passes;              // the filter's stage-1 passes (steps 1, 2, ..., 2^(passes - 1))
  uint correctIrradiance;  // 1: output the ratio times the filtered mean weight (ShadowEstimator)

  float normalPower;  // weight max(0, n.n')^normalPower
  float planeSigma;   // tangent-plane distance, in pixel footprints x stepSize, at weight e^-1/2
  float ratioSigma;   // ratio difference at weight e^-1/2 (from the second pass on: the first pass sees
                      // raw ratios, with k = 1 only 0 or 1, which would stop every tap)
  float sigmaFade;    // ratio sigma x N^-sigmaFade for a ratio accumulated over N frames

  float lghError;     // f: the LGH irradiance's expected relative error (the prior spread of D)
  uint tilesPerAxis;  // n: the interleaving the estimate was made with (1: none)
  uint pad0, pad1;
};
GPU_CHECK_OFFSET(ShadowFilterUniforms, normalPower, 16);
GPU_CHECK_OFFSET(ShadowFilterUniforms, lghError, 32);
GPU_CHECK_SIZE(ShadowFilterUniforms, 48);

GPU_NAMESPACE_END
#endif
