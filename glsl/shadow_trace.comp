#version 450 core
// The shadow-ray pass's rays, traced (after shadow_rays.comp queued them): one queued ray an invocation,
// any-hit through the scene's BVH; a blocked ray zeroes its slot's weight, so that the sum of a pixel's
// slot weights is sum w V (shadow_ratio.comp). The queue holds only the rays to trace, in the order they
// were queued: a SIMD group's lanes (llvmpipe's, a GPU warp's) trace neighbouring pixels' rays, and none
// waits on a slot that needed no ray. A queued ray is its target and slot; its origin is the slot's
// pixel's surface point, read again from the G-buffer.
layout(local_size_x = 64) in;  // kShadowTraceGroupSize
#include "shared/bindings.h"
#include "shared/bvh_traverse.glsl"
#include "shared/gbuffer.glsl"
#include "shared/ray_offset.h"
#include "shared/shadow_ray.glsl"
#include "shared/shadow_ray_types.h"

// The queue: ShadowRayQueueCounts, then a QueuedShadowRay a texel.
layout(binding = LGH_TEXTURE_SHADOW_QUEUE) uniform usamplerBuffer queue;
layout(std430, binding = LGH_BINDING_PASS7) buffer SlotWeights { float slotWeights[]; };
layout(std140, binding = LGH_UBO_PASS) uniform ShadowRays { ShadowRayUniforms rays; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= texelFetch(queue, 0).x) return;
  uvec4 queued = texelFetch(queue, 1 + int(i));  // target, slot
  Surface s = loadSurface(ivec2(shadowSlotPixel(queued.w, rays.samples)));
  GpuRay ray = shadowRay(offsetRayOrigin(s.position, s.normal), uintBitsToFloat(queued.xyz));
  if (traceAnyHit(ray.origin, ray.direction, ray.tMin, ray.tMax)) slotWeights[queued.w] = 0.0;
}
