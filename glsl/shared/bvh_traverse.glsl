// BVH traversal for compute shaders: any-hit (shadow rays) and closest-hit (VPL paths, tests).
#ifndef LGH_BVH_TRAVERSE_GLSL
#define LGH_BVH_TRAVERSE_GLSL
#include "shared/bindings.h"
#include "shared/bvh_types.h"
#include "shared/ray_triangle.h"
#include "shared/scene_materials.glsl"

layout(std430, binding = LGH_BINDING_BVH_NODES) readonly buffer BvhNodes { BvhNode bvhNodes[]; };
layout(std430, binding = LGH_BINDING_BVH_TRIANGLES) readonly buffer BvhTriangles { BvhTriangle bvhTriangles[]; };

struct RayHit {
  float t;
  uint sceneTriangle;
  uint bvhTriangle;   // index into bvhTriangles (for the geometric normal)
  vec2 barycentrics;  // (u, v): weights of vertices 1 and 2
};

// Slab test; returns the entry distance or +inf for a miss. Boxes are padded at build time, so a
// ray grazing a flat (axis-aligned) box still enters it despite rounding.
float bvhEnterBox(vec3 boundsMin, vec3 boundsMax, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  vec3 t0 = (boundsMin - origin) * invDirection;
  vec3 t1 = (boundsMax - origin) * invDirection;
  vec3 tSmall = min(t0, t1), tLarge = max(t0, t1);
  float tEnter = max(max(tSmall.x, tSmall.y), max(tSmall.z, tMin));
  float tExit = min(min(tLarge.x, tLarge.y), min(tLarge.z, tMax));
  return tEnter <= tExit ? tEnter : uintBitsToFloat(0x7f800000u);
}

// Walks the BVH; with anyHit it stops at the first hit inside (tMin, tMax). Hits on triangles of
// alphaMode MASK materials count only where the surface is not cut out (so cut-outs let light and
// shadow rays through, as they let the camera see through). The build keeps the
// depth below kBvhStackSize, and only one node is pushed per level, so the stack cannot overflow.
bool bvhTrace(vec3 origin, vec3 direction, float tMin, float tMax, bool anyHit, out RayHit hit) {
  hit.t = tMax;
  hit.sceneTriangle = 0xffffffffu;
  hit.bvhTriangle = 0xffffffffu;
  hit.barycentrics = vec2(0.0);
  if (bvhNodes.length() == 0) return false;
  // A zero direction component gives +-inf in invDirection, never NaN: keep it away from 0 exactly.
  vec3 safeDirection = mix(direction, vec3(1e-30) * sign(direction + vec3(1e-38)), lessThan(abs(direction), vec3(1e-30)));
  vec3 invDirection = 1.0 / safeDirection;

  uint stack[kBvhStackSize];
  uint stackSize = 0u;
  uint node = 0u;
  if (isinf(bvhEnterBox(bvhNodes[0].boundsMin, bvhNodes[0].boundsMax, origin, invDirection, tMin, tMax))) return false;
  bool found = false;
  while (true) {
    BvhNode current = bvhNodes[node];
    if (current.triangleCount > 0u) {
      for (uint i = 0u; i < current.triangleCount; ++i) {
        uint triangleIndex = current.firstChildOrTriangle + i;
        BvhTriangle tri = bvhTriangles[triangleIndex];
        vec3 tuv;
        if (intersectTriangle(origin, direction, tri.v0, tri.edge1, tri.edge2, tMin, hit.t, tuv) &&
            ((tri.flags & kBvhTriangleAlphaMasked) == 0u || !surfaceCutOut(tri.sceneTriangle, tuv.yz))) {
          hit.t = tuv.x;
          hit.barycentrics = tuv.yz;
          hit.sceneTriangle = tri.sceneTriangle;
          hit.bvhTriangle = triangleIndex;
          found = true;
          if (anyHit) return true;
        }
      }
    } else {
      uint left = current.firstChildOrTriangle, right = left + 1u;
      float tLeft = bvhEnterBox(bvhNodes[left].boundsMin, bvhNodes[left].boundsMax, origin, invDirection, tMin, hit.t);
      float tRight = bvhEnterBox(bvhNodes[right].boundsMin, bvhNodes[right].boundsMax, origin, invDirection, tMin, hit.t);
      bool hitLeft = !isinf(tLeft), hitRight = !isinf(tRight);
      if (hitLeft && hitRight) {
        // Nearer child first; the farther one waits on the stack.
        bool leftFirst = tLeft <= tRight;
        stack[stackSize++] = leftFirst ? right : left;
        node = leftFirst ? left : right;
        continue;
      }
      if (hitLeft || hitRight) {
        node = hitLeft ? left : right;
        continue;
      }
    }
    if (stackSize == 0u) break;
    node = stack[--stackSize];
  }
  return found;
}

bool traceAnyHit(vec3 origin, vec3 direction, float tMin, float tMax) {
  RayHit unused;
  return bvhTrace(origin, direction, tMin, tMax, true, unused);
}

bool traceClosestHit(vec3 origin, vec3 direction, float tMin, float tMax, out RayHit hit) {
  return bvhTrace(origin, direction, tMin, tMax, false, hit);
}

#endif
