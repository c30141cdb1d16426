// BVH traversal for compute shaders: any-hit (shadow rays: the first hit ends the ray) and closest-hit
// (VPL paths, tests), over the scene's BVH in the node layout the shader is compiled for
// (LGH_BVH_LAYOUT = gpu::kBvhLayout*, which gl::TracingProgram defines from the scene): each layout's
// traversal is one file, with the same functions.
#ifndef LGH_BVH_TRAVERSE_GLSL
#define LGH_BVH_TRAVERSE_GLSL
#include "shared/bindings.h"
#include "shared/bvh_types.h"
#include "shared/ray_triangle.h"
#include "shared/scene_materials.glsl"

#ifndef LGH_BVH_LAYOUT
#error "a shader that traces rays is compiled for the scene's BVH layout (gl::TracingProgram defines LGH_BVH_LAYOUT)"
#endif

// With LGH_BVH_COUNTERS (lgh-bench rays) the traversal counts its work in these, per invocation: inner
// nodes whose children's boxes it tested, those box tests, and triangle tests.
#ifdef LGH_BVH_COUNTERS
uint bvhInnerNodes = 0u, bvhBoxTests = 0u, bvhTriangleTests = 0u;
#define LGH_BVH_COUNT(counter, n) counter += (n)
#else
#define LGH_BVH_COUNT(counter, n)
#endif

// The BVH as texels (render/scene/gpu_bvh.h): a float and an integer view of its nodes and of its triangles,
// whose structs (shared/bvh_types.h) are whole texels.
layout(binding = LGH_TEXTURE_BVH_NODE_FLOATS) uniform samplerBuffer bvhNodeFloats;
layout(binding = LGH_TEXTURE_BVH_NODE_WORDS) uniform usamplerBuffer bvhNodeWords;
layout(binding = LGH_TEXTURE_BVH_TRIANGLE_FLOATS) uniform samplerBuffer bvhTriangleFloats;
layout(binding = LGH_TEXTURE_BVH_TRIANGLE_WORDS) uniform usamplerBuffer bvhTriangleWords;

// BvhTriangle `index`'s vertex and edges (its first three vec3s; the words beside them are read on a hit).
void bvhTriangleGeometry(uint index, out vec3 v0, out vec3 edge1, out vec3 edge2) {
  int texel = kBvhTriangleTexels * int(index);
  v0 = texelFetch(bvhTriangleFloats, texel).xyz;
  edge1 = texelFetch(bvhTriangleFloats, texel + 1).xyz;
  edge2 = texelFetch(bvhTriangleFloats, texel + 2).xyz;
}
uint bvhSceneTriangle(uint index) { return texelFetch(bvhTriangleWords, kBvhTriangleTexels * int(index)).w; }
uint bvhTriangleFlags(uint index) { return texelFetch(bvhTriangleWords, kBvhTriangleTexels * int(index) + 1).w; }

struct RayHit {
  float t;
  uint sceneTriangle;
  uint bvhTriangle;   // index into bvhTriangles (for the geometric normal)
  vec2 barycentrics;  // (u, v): weights of vertices 1 and 2
};

RayHit bvhNoHit(float tMax) { return RayHit(tMax, 0xffffffffu, 0xffffffffu, vec2(0.0)); }

// A zero direction component gives +-inf in the inverse direction, never NaN: it is kept away from 0.
vec3 bvhInverseDirection(vec3 direction) {
  return 1.0 / mix(direction, vec3(1e-30) * sign(direction + vec3(1e-38)), lessThan(abs(direction), vec3(1e-30)));
}

// Tests the leaf's triangles against (tMin, hit.t); true on a hit (hit updated). Hits on triangles of
// alphaMode MASK materials count only where the surface is not cut out (so cut-outs let light and shadow
// rays through, as they let the camera see through).
bool bvhTestLeaf(uint first, uint count, vec3 origin, vec3 direction, float tMin, bool anyHit, inout RayHit hit) {
  bool found = false;
  for (uint i = 0u; i < count; ++i) {
    uint triangleIndex = first + i;
    LGH_BVH_COUNT(bvhTriangleTests, 1u);
    vec3 v0, edge1, edge2, tuv;
    bvhTriangleGeometry(triangleIndex, v0, edge1, edge2);
    if (!intersectTriangle(origin, direction, v0, edge1, edge2, tMin, hit.t, tuv)) continue;
    uint sceneTriangle = bvhSceneTriangle(triangleIndex);
    if ((bvhTriangleFlags(triangleIndex) & kBvhTriangleAlphaMasked) == 0u || !surfaceCutOut(sceneTriangle, tuv.yz)) {
      hit.t = tuv.x;
      hit.barycentrics = tuv.yz;
      hit.sceneTriangle = sceneTriangle;
      hit.bvhTriangle = triangleIndex;
      found = true;
      if (anyHit) return true;
    }
  }
  return found;
}

#if LGH_BVH_LAYOUT == 1  // kBvhLayoutWide4
#include "shared/bvh_wide4.glsl"
#elif LGH_BVH_LAYOUT == 2  // kBvhLayoutCompressed8
#include "shared/bvh_compressed8.glsl"
#else
#include "shared/bvh_binary.glsl"
#endif

bool traceAnyHit(vec3 origin, vec3 direction, float tMin, float tMax) {
  RayHit unused;
  return bvhTrace(origin, direction, tMin, tMax, true, unused);
}

bool traceClosestHit(vec3 origin, vec3 direction, float tMin, float tMax, out RayHit hit) {
  return bvhTrace(origin, direction, tMin, tMax, false, hit);
}

#endif
