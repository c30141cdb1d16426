// Uniforms of the shadow-ray pass (one block, std140), shared by shadow_rays.comp and C++ (ShadowRayPass).
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
  uint pad0, pad1;
};
GPU_CHECK_OFFSET(ShadowRayUniforms, races, 16);
GPU_CHECK_OFFSET(ShadowRayUniforms, spread, 32);
GPU_CHECK_OFFSET(ShadowRayUniforms, alpha, 48);
GPU_CHECK_OFFSET(ShadowRayUniforms, bruteForce, 64);
GPU_CHECK_SIZE(ShadowRayUniforms, 80);

GPU_NAMESPACE_END
#endif
