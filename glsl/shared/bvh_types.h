// Flattened BVH as the GPU reads it (std430), written by render/scene/bvh.cpp.
#ifndef LGH_BVH_TYPES_H
#define LGH_BVH_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// Nodes in depth-first order. An interior node's two children are adjacent (firstChildOrTriangle and
// firstChildOrTriangle + 1) so traversal can test both boxes and descend into the nearer first.
GPU_STRUCT(BvhNode) {
  vec3 boundsMin;
  uint firstChildOrTriangle;  // interior: index of the first child; leaf: index of its first BvhTriangle
  vec3 boundsMax;
  uint triangleCount;  // 0 for interior nodes
};
GPU_CHECK_SIZE(BvhNode, 32);
GPU_CHECK_OFFSET(BvhNode, boundsMax, 16);

// Triangles in BVH leaf order, pre-arranged for Moller-Trumbore (a vertex and two edges).
GPU_STRUCT(BvhTriangle) {
  vec3 v0;
  uint sceneTriangle;  // index into the scene's triangle list (materials, attributes)
  vec3 edge1;          // v1 - v0
  uint flags;          // kBvhTriangleAlphaMasked: hits are alpha-tested against the material
  vec3 edge2;          // v2 - v0
  float pad2;
};
GPU_CHECK_SIZE(BvhTriangle, 48);

GPU_CONST uint kBvhStackSize = 64u;
GPU_CONST uint kBvhTriangleAlphaMasked = 1u;

GPU_NAMESPACE_END
#endif
