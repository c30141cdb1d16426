// Uniforms of the irradiance filter (irradiance_atrous.comp; one block per dispatch, std140), shared with
// C++ (IrradianceFilterPass).
#ifndef LGH_IRRADIANCE_FILTER_TYPES_H
#define LGH_IRRADIANCE_FILTER_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// Scalars in groups of four (see gpu_prelude.h).
GPU_STRUCT(IrradianceFilterUniforms) {
  int stepSize;       // the holes between taps: 1, 2, ..., 2^(passes - 1)
  int passes;         // the filter's passes
  float normalPower;  // weight max(0, n.n')^normalPower
  float planeSigma;   // tangent-plane distance, in pixel footprints x stepSize, at weight e^-1/2

  float luminanceSigma;  // relative luminance difference at weight e^-1/2 (from the second pass on)
  float sigmaFade;       // luminance sigma x N^-sigmaFade over N accumulated frames
  float frames;          // N: the frames the estimate holds (1: one frame)
  float pad0;
};
GPU_CHECK_OFFSET(IrradianceFilterUniforms, luminanceSigma, 16);
GPU_CHECK_SIZE(IrradianceFilterUniforms, 32);

GPU_NAMESPACE_END
#endif
