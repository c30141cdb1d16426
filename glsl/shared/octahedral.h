// Octahedral unit-vector encoding in 32 bits (Cigolle et al. 2014): about 1e-4 rad of error, half
// the bytes of a vec3. Shared so that the CPU reference decodes exactly what the GPU decodes.
#ifndef LGH_OCTAHEDRAL_H
#define LGH_OCTAHEDRAL_H
#include "shared/gpu_prelude.h"
#ifdef __cplusplus
#include <glm/gtc/packing.hpp>
#endif

GPU_NAMESPACE_BEGIN

GPU_FUNC vec2 octWrap(vec2 v) {
  return vec2((1.0f - abs(v.y)) * (v.x >= 0.0f ? 1.0f : -1.0f), (1.0f - abs(v.x)) * (v.y >= 0.0f ? 1.0f : -1.0f));
}

GPU_FUNC uint octEncode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = vec2(n.x, n.y) * (1.0f / max(l1, 1e-30f));
  if (n.z < 0.0f) p = octWrap(p);
#ifdef __cplusplus
  return glm::packSnorm2x16(p);
#else
  return packSnorm2x16(p);
#endif
}

GPU_FUNC vec3 octDecode(uint bits) {
#ifdef __cplusplus
  vec2 p = glm::unpackSnorm2x16(bits);
#else
  vec2 p = unpackSnorm2x16(bits);
#endif
  vec3 n = vec3(p.x, p.y, 1.0f - abs(p.x) - abs(p.y));
  if (n.z < 0.0f) {
    vec2 w = octWrap(vec2(n.x, n.y));
    n.x = w.x;
    n.y = w.y;
  }
#ifdef __cplusplus
  return glm::normalize(n);
#else
  return normalize(n);
#endif
}

GPU_NAMESPACE_END
#endif
