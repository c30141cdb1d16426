// Flattened BVH as the GPU reads it, written by render/scene/bvh.cpp in one of three node layouts
// (gpu::kBvhLayout*): binary nodes (BvhNode), 4-wide nodes (BvhWideNode) or compressed 8-wide nodes
// (BvhCompressedNode), over the same triangles. A
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
GPU_CONST int kBvhCompressedNodeTexels = 5;

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

// A compressed 8-wide node (Ylitie, Karras & Laine, "Efficient incoherent ray traversal on GPUs through
// compressed wide BVHs", HPG 2017): its children's boxes quantized to 8 bits per bound on a grid of the
// node's own, from `origin` in steps of a power of two per axis, rounded outward (the decoded box,
// origin + q step in float, holds the padded child box: bvh.cpp checks it as the GPU computes it). The
// inner children are consecutive nodes from childBase, the leaves' triangles consecutive from
// triangleBase, so one byte per child says which: kBvhMetaEmpty, kBvhMetaInner | i (node childBase + i),
// or a leaf, (count - 1) << kBvhMetaCountShift | offset (count <= kBvhCompressedMaxLeafSize triangles
// from triangleBase + offset). Byte i of a pair of words is child i's: child 0-3 in the first word, 4-7
// in the second.
GPU_STRUCT(BvhCompressedNode) {
  vec3 origin;
  uint exponents;  // bytes 0-2: each axis's step as a float's biased exponent (2^(e - 127)); 3: slots in use
  uint childBase;
  uint triangleBase;
  uvec2 meta;
  uvec4 lowerXY;       // xy: children's lower x bounds; zw: lower y
  uvec4 lowerZUpperX;  // xy: lower z; zw: upper x
  uvec4 upperYZ;       // xy: upper y; zw: upper z
};
GPU_CHECK_SIZE(BvhCompressedNode, 16 * kBvhCompressedNodeTexels);
GPU_CHECK_OFFSET(BvhCompressedNode, exponents, 12);
GPU_CHECK_OFFSET(BvhCompressedNode, meta, 24);
GPU_CHECK_OFFSET(BvhCompressedNode, lowerXY, 32);

GPU_CONST uint kBvhCompressedWidth = 8u;
GPU_CONST uint kBvhCompressedMaxLeafSize = 4u;  // count - 1 (2 bits) and offset (5 bits: at most 7 x 4) fit a byte
GPU_CONST uint kBvhMetaEmpty = 0xffu;
GPU_CONST uint kBvhMetaInner = 0x80u;
GPU_CONST uint kBvhMetaInnerIndexMask = 7u;           // inner: the child's index from childBase
GPU_CONST uint kBvhMetaCountShift = 5u;               // leaf: count - 1 above the offset
GPU_CONST uint kBvhMetaOffsetMask = 31u;              // leaf: the first triangle's offset from triangleBase
GPU_CONST uint kBvhCompressedNodeMask = 0x00ffffffu;  // the traversal's stack: node | slots << 24

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
GPU_CONST uint kBvhLayoutCompressed8 = 2u;
GPU_CONST uint kBvhWidth = 4u;
GPU_CONST uint kBvhLeaf = 0x80000000u;
GPU_CONST uint kBvhLeafCountShift = 27u;  // 4 bits: 1-16 triangles
GPU_CONST uint kBvhLeafCountMask = 15u;
GPU_CONST uint kBvhLeafFirstMask = 0x07ffffffu;
GPU_CONST uint kBvhEmptyChild = 0xffffffffu;
GPU_CONST uint kBvhMaxLeafSize = 16u;

GPU_CONST uint kBvhStackSize = 64u;
GPU_CONST uint kBvhTriangleAlphaMasked = 1u;

GPU_NAMESPACE_END
#endif
