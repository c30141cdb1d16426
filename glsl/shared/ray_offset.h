// Ray origins that leave a surface without self-intersection at every scene scale.
#ifndef LGH_RAY_OFFSET_H
#define LGH_RAY_OFFSET_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// Moves p off the surface along the normal n (pointing to the side the ray leaves from) by a fixed
// number of float ulps, so the step grows with |p| exactly as float rounding error does: the same
// offset works for a 1 mm model at the origin and for a scene 1e5 m away (Waechter & Binder,
// "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, ch. 6). Near the
// origin, where ulps are tiny, a small absolute step takes over. The integer scale is larger than
// the chapter's because G-buffer positions come from interpolation, not from the exact hit.
GPU_FUNC vec3 offsetRayOrigin(vec3 p, vec3 n) {
  const float kOriginRegion = 1.0f / 32.0f;
  const float kFloatScale = 1.0f / 16384.0f;
  const float kIntScale = 1024.0f;
  ivec3 ofs = ivec3(kIntScale * n.x, kIntScale * n.y, kIntScale * n.z);
  vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0f ? -ofs.x : ofs.x)),
                 intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0f ? -ofs.y : ofs.y)),
                 intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0f ? -ofs.z : ofs.z)));
  return vec3(abs(p.x) < kOriginRegion ? p.x + kFloatScale * n.x : pi.x,
              abs(p.y) < kOriginRegion ? p.y + kFloatScale * n.y : pi.y,
              abs(p.z) < kOriginRegion ? p.z + kFloatScale * n.z : pi.z);
}

GPU_NAMESPACE_END
#endif
