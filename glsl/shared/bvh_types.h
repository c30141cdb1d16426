// Flattened BVH as the GPU reads it, written by render/scene/bvh.cpp in one of two node layouts
// (gpu::kBvhLayout*): binary nodes (BvhNode) or 4-wide nodes (BvhWideNode), over the same triangles. A
// shader that traces is compiled for one layout (LGH_BVH_LAYOUT, shared/bvh_traverse.glsl). The traversal
// fetches them as 16-byte texels (render/scene/gpu_bvh.h), so each struct is whole texels, a vec3 and a
// 32-bit word to a texel: the checks below pin that.
#ifndef LGH_BVH_TYPES_H
#define LGH_BVH_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// 16-byte texels per struct, as the traversal fetches them.
GPU_CONST int kBvhNodeTexels = 2;
GPU_CONST int kBvhTriangleTexels = 3;
GPU_CONST int kBvhWideNodeTexels = 7;

// Nodes in depth-first order. An interior node's two children are adjacent (firstChildOrTriangle and
// firstChildOrTriangle + 1) so traversal can test both boxes and descend into the nearer first.
GPU_STRUCT(BvhNode) {
  vec3 boundsMin;
  uint firstChildOrTriangle;  // interior: index of the first child; leaf: index of its first BvhTriangle
  vec3 boundsMax;
  uint triangleCount;  // 0 for interior nodes
};
GPU_CHECK_SIZE(BvhNode, 16 * kBvhNodeTexels);
GPU_CHECK_OFFSET(BvhNode, firstChildOrTriangle, 12);
GPU_CHECK_OFFSET(BvhNode, boundsMax, 16);
GPU_CHECK_OFFSET(BvhNode, triangleCount, 28);

// Triangles in BVH leaf order, pre-arranged for Moller-Trumbore (a vertex and two edges).
GPU_STRUCT(BvhTriangle) {
  vec3 v0;
  uint sceneTriangle;  // index into the scene's triangle list (materials, attributes)
  vec3 edge1;          // v1 - v0
  uint flags;          // kBvhTriangleAlphaMasked: hits are alpha-tested against the material
  vec3 edge2;          // v2 - v0
  float pad2;
};
GPU_CHECK_SIZE(BvhTriangle, 16 * kBvhTriangleTexels);
GPU_CHECK_OFFSET(BvhTriangle, sceneTriangle, 12);
GPU_CHECK_OFFSET(BvhTriangle, edge1, 16);
GPU_CHECK_OFFSET(BvhTriangle, flags, 28);
GPU_CHECK_OFFSET(BvhTriangle, edge2, 32);

// A 4-wide node: its children's boxes side by side (one slab test for all four), and the children: an
// inner node's index, a leaf (kBvhLeaf | (count - 1) << kBvhLeafCountShift | first triangle), or
// kBvhEmptyChild (its box is not read).
GPU_STRUCT(BvhWideNode) {
  vec4 lowerX;
  vec4 upperX;
  vec4 lowerY;
  vec4 upperY;
  vec4 lowerZ;
  vec4 upperZ;
  uvec4 children;
};
GPU_CHECK_SIZE(BvhWideNode, 16 * kBvhWideNodeTexels);
GPU_CHECK_OFFSET(BvhWideNode, children, 96);

// A ray as benchmarks and tests hand it to the traversal, and as the shadow-ray pass records its own
// (lgh-bench rays): the hits wanted lie in (tMin, tMax); tMax <= tMin: no ray.
GPU_STRUCT(GpuRay) {
  vec3 origin;
  float tMin;
  vec3 direction;  // unit
  float tMax;
};
GPU_CHECK_SIZE(GpuRay, 32);
GPU_CHECK_OFFSET(GpuRay, direction, 16);

GPU_CONST uint kBvhLayoutBinary = 0u;
GPU_CONST uint kBvhLayoutWide4 = 1u;
GPU_CONST uint kBvhWidth = 4u;
GPU_CONST uint kBvhLeaf = 0x80000000u;
GPU_CONST uint kBvhLeafCountShift = 27u;  // 4 bits: 1-16 triangles
GPU_CONST uint kBvhLeafFirstMask = 0x07ffffffu;
GPU_CONST uint kBvhEmptyChild = 0xffffffffu;
GPU_CONST uint kBvhMaxLeafSize = 16u;

GPU_CONST uint kBvhStackSize = 64u;
GPU_CONST uint kBvhTriangleAlphaMasked = 1u;

GPU_NAMESPACE_END
#endif
