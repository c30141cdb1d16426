// Ray/triangle intersection, compiled as both C++ (the brute-force oracle in tests) and GLSL (BVH
// traversal), so a test comparing the two checks the traversal, not two formulas.
#ifndef LGH_RAY_TRIANGLE_H
#define LGH_RAY_TRIANGLE_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// Moller-Trumbore, double-sided (shadow rays must be blocked by back faces too).
// Returns true for a hit with tMin < t < tMax; hit = (t, u, v), barycentrics of v1 and v2.
// Degenerate (zero-area) triangles have det == 0 and never hit; no division by zero reaches the result.
GPU_FUNC bool intersectTriangle(vec3 origin, vec3 direction, vec3 v0, vec3 edge1, vec3 edge2, float tMin, float tMax,
                                GPU_OUT(vec3) hit) {
  vec3 p = cross(direction, edge2);
  float det = dot(edge1, p);
  if (det == 0.0f) return false;
  float invDet = 1.0f / det;
  vec3 s = origin - v0;
  float u = dot(s, p) * invDet;
  if (u < 0.0f || u > 1.0f) return false;
  vec3 q = cross(s, edge1);
  float v = dot(direction, q) * invDet;
  if (v < 0.0f || u + v > 1.0f) return false;
  float t = dot(edge2, q) * invDet;
  if (!(t > tMin && t < tMax)) return false;  // also rejects NaN
  hit = vec3(t, u, v);
  return true;
}

GPU_NAMESPACE_END
#endif
