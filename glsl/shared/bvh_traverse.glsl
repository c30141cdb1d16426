// BVH traversal for compute shaders: any-hit (shadow rays: the first hit ends the ray) and closest-hit
// (VPL paths, tests), over the scene's BVH as the shader is compiled for it (TracingProgram defines
// LGH_BVH_LAYOUT = gpu::kBvhLayout*, and LGH_BVH_ALPHA_MASKED where a triangle is alpha-masked): each
// layout's walk is one file with the same functions, which bvhTrace below drives.
#ifndef LGH_BVH_TRAVERSE_GLSL
#define LGH_BVH_TRAVERSE_GLSL
#include "shared/bindings.h"
#include "shared/bvh_types.h"
#include "shared/ray_triangle.h"
#include "shared/scene_materials.glsl"

#if !defined(LGH_BVH_LAYOUT) || !defined(LGH_BVH_ALPHA_MASKED)
#error \
    "a shader that traces rays is compiled for the scene's BVH (TracingProgram defines LGH_BVH_LAYOUT, LGH_BVH_ALPHA_MASKED)"
#endif

// With LGH_BVH_COUNTERS (lgh-bench rays) the traversal counts its work in these, per invocation: inner
// nodes whose children's boxes it tested, those box tests, and triangle tests.
#ifdef LGH_BVH_COUNTERS
uint bvhInnerNodes = 0u, bvhBoxTests = 0u, bvhTriangleTests = 0u;
#define LGH_BVH_COUNT(counter, n) counter += (n)
#else
#define LGH_BVH_COUNT(counter, n)
#endif

// The BVH as texels (render/scene/gpu_bvh.h): a float and an integer view of its nodes, an integer view of
// its triangles, whose structs (shared/bvh_types.h) are whole texels.
layout(binding = LGH_TEXTURE_BVH_NODE_FLOATS) uniform samplerBuffer bvhNodeFloats;
layout(binding = LGH_TEXTURE_BVH_NODE_WORDS) uniform usamplerBuffer bvhNodeWords;
layout(binding = LGH_TEXTURE_BVH_TRIANGLE_WORDS) uniform usamplerBuffer bvhTriangleWords;

// BvhTriangle `index`, its three texels read as integers (the vertex's and edges' bits cast back exactly).
BvhTriangle bvhTriangle(uint index) {
  int texel = kBvhTriangleTexels * int(index);
  uvec4 t0 = texelFetch(bvhTriangleWords, texel), t1 = texelFetch(bvhTriangleWords, texel + 1),
        t2 = texelFetch(bvhTriangleWords, texel + 2);
  return BvhTriangle(uintBitsToFloat(t0.xyz), t0.w, uintBitsToFloat(t1.xyz), t1.w, uintBitsToFloat(t2.xyz),
                     uintBitsToFloat(t2.w));
}

struct RayHit {
  float t;
  uint sceneTriangle;
  uint bvhTriangle;   // index into bvhTriangles (for the geometric normal)
  vec2 barycentrics;  // (u, v): weights of vertices 1 and 2
};

const uint kBvhNoTriangle = 0xffffffffu;
RayHit bvhNoHit(float tMax) { return RayHit(tMax, kBvhNoTriangle, kBvhNoTriangle, vec2(0.0)); }

// A zero direction component gives +-inf in the inverse direction, never NaN: it is kept away from 0.
vec3 bvhInverseDirection(vec3 direction) {
  return 1.0 / mix(direction, vec3(1e-30) * sign(direction + vec3(1e-38)), lessThan(abs(direction), vec3(1e-30)));
}

// The triangles of a leaf still to test: a walk through the BVH stops at a hit on an alpha-masked
// triangle and resumes after it once the caller has tested the cut-out.
struct BvhLeafCursor {
  uint next;  // BvhTriangle index
  uint left;
};

// What testing a leaf's triangles ended in.
const uint kBvhLeafTested = 0u;   // all tested (closest-hit: a nearer opaque hit is in hit)
const uint kBvhLeafBlocked = 1u;  // any-hit: an opaque triangle ends the ray (in hit)
const uint kBvhLeafMasked = 2u;   // a hit on an alpha-masked triangle, in candidate: test its cut-out

// Tests the cursor's triangles against (tMin, hit.t), advancing it. A triangle is three texels (its ids
// ride in the vertex's and first edge's w), and a hit on an alpha-masked one is handed back
// rather than tested here: the cut-out reads the material, the vertices and a texture, and a SIMD
// machine (llvmpipe; a GPU's divergent warp) runs that code for every lane on every step of the walk's
// loop that it is inside, whether a lane takes it or not. Outside the loop it runs once per candidate.
uint bvhTestLeaf(inout BvhLeafCursor cursor, vec3 origin, vec3 direction, float tMin, bool anyHit, inout RayHit hit,
                 out RayHit candidate) {
  while (cursor.left > 0u) {
    uint index = cursor.next++;
    --cursor.left;
    LGH_BVH_COUNT(bvhTriangleTests, 1u);
    BvhTriangle triangle = bvhTriangle(index);
    vec3 tuv;
    if (!intersectTriangle(origin, direction, triangle.v0, triangle.edge1, triangle.edge2, tMin, hit.t, tuv)) continue;
    RayHit found = RayHit(tuv.x, triangle.sceneTriangle, index, tuv.yz);
#if LGH_BVH_ALPHA_MASKED
    if ((triangle.flags & kBvhTriangleAlphaMasked) != 0u) {
      candidate = found;
      return kBvhLeafMasked;
    }
#endif
    hit = found;
    if (anyHit) return kBvhLeafBlocked;
  }
  return kBvhLeafTested;
}

// A candidate on an alpha-masked triangle counts where the surface is not cut out (so cut-outs let
// light and shadow rays through, as they let the camera see through); true when it does (hit updated).
bool bvhAcceptMasked(RayHit candidate, inout RayHit hit) {
#if LGH_BVH_ALPHA_MASKED
  if (surfaceCutOut(candidate.sceneTriangle, candidate.barycentrics)) return false;
  hit = candidate;
  return true;
#else
  return false;  // not reached: no triangle is alpha-masked
#endif
}

// The walk's stack (each layout's entries), private to the invocation.
uint bvhStack[kBvhStackSize];

// Each layout's file defines its walk's state (BvhWalk), bvhWalkStart (false: nothing to walk) and
// bvhWalkToLeaf (walks nodes until a leaf whose box the ray enters within (tMin, tMax); false when none
// is left).
#if LGH_BVH_LAYOUT == 1  // kBvhLayoutWide4
#include "shared/bvh_wide4.glsl"
#elif LGH_BVH_LAYOUT == 2  // kBvhLayoutCompressed8
#include "shared/bvh_compressed8.glsl"
#else
#include "shared/bvh_binary.glsl"
#endif

// The walk, the leaves' triangles and the cut-out tests as three loops, shaped by how SIMD lanes
// (llvmpipe's, a GPU warp's) run a loop: every lane runs every branch of the body, masked, until no lane
// is left in the loop. Innermost (bvhWalkToLeaf), the nodes until a leaf: a lane with a leaf waits for
// the others to reach theirs, so no step pays for both a node's boxes and triangles. Around it, the
// leaf's triangles, then the next leaf. Outermost, the cut-out test of the alpha-masked hit that the
// walk stopped at (bvhTestLeaf), run once per candidate rather than on every step (measurements.md,
// "Loops that SIMD lanes run together").
bool bvhTrace(vec3 origin, vec3 direction, float tMin, float tMax, bool anyHit, out RayHit hit) {
  hit = bvhNoHit(tMax);
  vec3 invDirection = bvhInverseDirection(direction);
  BvhWalk walk;
  if (!bvhWalkStart(walk, origin, invDirection, tMin, tMax)) return false;
  BvhLeafCursor leaf = BvhLeafCursor(0u, 0u);
  RayHit candidate;
  while (true) {
    while (true) {
      uint tested = bvhTestLeaf(leaf, origin, direction, tMin, anyHit, hit, candidate);
      if (tested == kBvhLeafBlocked) return true;
      if (tested == kBvhLeafMasked) break;
      if (!bvhWalkToLeaf(walk, origin, invDirection, tMin, hit.t, anyHit, leaf))
        return hit.bvhTriangle != kBvhNoTriangle;
    }
    if (bvhAcceptMasked(candidate, hit) && anyHit) return true;
  }
  return false;  // not reached
}

bool traceAnyHit(vec3 origin, vec3 direction, float tMin, float tMax) {
  RayHit unused;
  return bvhTrace(origin, direction, tMin, tMax, true, unused);
}

bool traceClosestHit(vec3 origin, vec3 direction, float tMin, float tMax, out RayHit hit) {
  return bvhTrace(origin, direction, tMin, tMax, false, hit);
}

#endif
