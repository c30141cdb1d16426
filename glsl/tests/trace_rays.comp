#version 450 core
// Test kernel: traces one ray per invocation through the BVH, closest-hit and any-hit.
layout(local_size_x = 64) in;
#include "shared/dispatch.glsl"
#include "shared/bvh_traverse.glsl"
#include "tests/test_types.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Rays { TestRay rays[]; };
layout(std430, binding = LGH_BINDING_PASS1) writeonly buffer Hits { TestHit hits[]; };

void main() {
  uint i = lghGlobalIndex();
  if (i >= uint(rays.length())) return;
  TestRay ray = rays[i];
  RayHit hit;
  bool found = traceClosestHit(ray.originTMin.xyz, ray.directionTMax.xyz, ray.originTMin.w, ray.directionTMax.w, hit);
  bool any = traceAnyHit(ray.originTMin.xyz, ray.directionTMax.xyz, ray.originTMin.w, ray.directionTMax.w);
  hits[i] = TestHit(found ? hit.t : -1.0, found ? hit.sceneTriangle : 0xffffffffu, any ? 1u : 0u, 0u);
}
