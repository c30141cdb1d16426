// A shadow ray as the shadow-ray pass makes it, once where it queues the ray (shadow_rays.comp) and again
// where it traces it (shadow_trace.comp): from the pixel's surface point, offset along its normal
// (offsetRayOrigin), towards the target, stopping short of it by a relative margin (VPLs sit on
// surfaces, and so may a cluster's centre). tMax 0: no ray (the target is the origin).
#ifndef LGH_SHADOW_RAY_GLSL
#define LGH_SHADOW_RAY_GLSL
#include "shared/bvh_types.h"
#include "shared/frame.glsl"

// The pass numbers the slots of its queue and weights (y W + x) k + j: pixel (x, y)'s first slot, and
// the pixel of slot `slot`.
uint shadowFirstSlot(uvec2 pixel, uint samples) { return (pixel.y * uint(frame.resolution.x) + pixel.x) * samples; }
uvec2 shadowSlotPixel(uint slot, uint samples) {
  uint pixel = slot / samples, width = uint(frame.resolution.x);
  return uvec2(pixel % width, pixel / width);
}

GpuRay shadowRay(vec3 origin, vec3 target) {
  vec3 toLight = target - origin;
  float rayLength = length(toLight);
  if (!(rayLength > 0.0)) return GpuRay(origin, 0.0, vec3(0.0), 0.0);
  return GpuRay(origin, 0.0, toLight / rayLength, rayLength * (1.0 - 1e-3));
}

#endif
