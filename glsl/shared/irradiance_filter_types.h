// Uniforms of the lightcuts' variance-guided filter (irradiance_atrous.comp; one block per dispatch,
// std140), shared with C++ (IrradianceFilterPass).
#ifndef LGH_IRRADIANCE_FILTER_TYPES_H
#define LGH_IRRADIANCE_FILTER_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kIrradianceVariance = 0u;  // stage 0: the m x m resolve and each pixel's luminance variance
GPU_CONST uint kIrradiancePass = 1u;      // stage 1: one a-trous pass with holes of stepSize

// Scalars in groups of four (see gpu_prelude.h).
GPU_STRUCT(IrradianceFilterUniforms) {
  uint stage;       // kIrradiance*
  int stepSize;     // stage 1: the holes between taps: 1, 2, ..., 2^(passes - 1)
  int passes;       // the filter's stage-1 passes
  uint interleave;  // m: the lightcuts' m x m interleaving (1: none)

  float normalPower;     // weight max(0, n.n')^normalPower
  float planeSigma;      // tangent-plane distance, in pixel footprints x stepSize, at weight e^-1/2
  float luminanceSigma;  // sigma_l: the luminance stop's scale, in standard deviations of the difference
  float sigmaFade;       // floor(sigmaFade log2 N) widest passes skipped over N accumulated frames

  uint hasMoments;   // 1: the accumulation's moments (ratio image: g the mean's variance, a N) are bound
  uint minTemporal;  // frames from which the temporal variance replaces the spatial estimate
  uint pad0, pad1;
};
GPU_CHECK_OFFSET(IrradianceFilterUniforms, normalPower, 16);
GPU_CHECK_OFFSET(IrradianceFilterUniforms, hasMoments, 32);
GPU_CHECK_SIZE(IrradianceFilterUniforms, 48);

GPU_NAMESPACE_END
#endif
