// Structs of the GL test kernels (glsl/tests/*.comp), shared with the C++ tests that fill and read them.
#ifndef LGH_TEST_TYPES_H
#define LGH_TEST_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// tests/lgh_shading.comp: one evaluation of the blending functions and a light's contribution.
GPU_STRUCT(ShadingCase) {
  vec4 lightPosOmni;    // xyz light position, w omni fraction
  vec4 intensityClamp;  // rgb intensity, w clamp distance
  vec4 meanNormalD;     // xyz mean normal, w distance for the blend test
  vec4 pointRadius;     // xyz shading point, w blend radius R
  vec4 normalRole;      // xyz shading normal, w role
};
GPU_CHECK_SIZE(ShadingCase, 80);

// tests/trace_rays.comp: one ray and what the BVH found for it.
GPU_STRUCT(TestRay) {
  vec4 originTMin;
  vec4 directionTMax;
};
GPU_CHECK_SIZE(TestRay, 32);

GPU_STRUCT(TestHit) {
  float t;  // closest hit, or a negative value for none
  uint sceneTriangle;
  uint anyHit;  // the any-hit query's answer (0 or 1)
  uint pad;
};
GPU_CHECK_SIZE(TestHit, 16);

GPU_NAMESPACE_END
#endif
