#version 450 core
// lgh-bench rays: one ray per invocation, any-hit through the scene's BVH (in the layout this program is
// compiled for), as the frame's shadow rays are traced; 1 where something blocks it. With LGH_BVH_COUNTERS,
// also the traversal's work per ray.
layout(local_size_x = 64) in;
#include "shared/dispatch.glsl"
#include "shared/bvh_traverse.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Rays { GpuRay rays[]; };
layout(std430, binding = LGH_BINDING_PASS1) writeonly buffer Blocked { uint blocked[]; };
#ifdef LGH_BVH_COUNTERS
// Per ray: inner nodes, box tests, triangle tests (shared/bvh_traverse.glsl's counters).
layout(std430, binding = LGH_BINDING_PASS2) writeonly buffer Work { uvec4 work[]; };
#endif
uniform uint rayCount;

void main() {
  uint i = lghGlobalIndex();
  if (i >= rayCount) return;
  GpuRay ray = rays[i];
  blocked[i] = traceAnyHit(ray.origin, ray.direction, ray.tMin, ray.tMax) ? 1u : 0u;
#ifdef LGH_BVH_COUNTERS
  work[i] = uvec4(bvhInnerNodes, bvhBoxTests, bvhTriangleTests, 0u);
#endif
}
