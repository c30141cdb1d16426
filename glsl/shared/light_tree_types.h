// The light tree of real-time stochastic lightcuts (Lin & Yuksel 2020, §3.1; docs/design.md §12): a
// perfect binary tree over the input lights S0, Morton-ordered, as a 1-based heap (root 1, children of
// node i at 2i and 2i + 1, the 2^(L-1) leaves from index 2^(L-1) on), shared by the tree build
// (light_tree.comp), the cuts and the sampling (rtslc.comp) and the CPU reference (lgh/light_tree.h).
#ifndef LGH_LIGHT_TREE_TYPES_H
#define LGH_LIGHT_TREE_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kTreeNoLight = 0xffffffffu;  // GpuLightTreeNode::lightIndex of internal nodes and padding leaves
GPU_CONST uint kMortonLevels = 1024u;       // per axis: 30-bit Morton codes
GPU_CONST uint kMaxCutNodes = 32u;          // a cut's largest size (the paper's MAX_CUT_NODES)
GPU_CONST uint kNoCutNode = 0u;             // an unused cut slot (node 0 does not exist)

// 32 bytes, as the authors' GPU node: two nodes per 64-byte line. No child pointers (the heap's indices)
// and no orientation cones (the paper's GPU tree has none either). An empty node (no lit light below)
// has intensity 0 and the inverted box (+FLT_MAX, -FLT_MAX).
GPU_STRUCT(GpuLightTreeNode) {
  vec3 boundMin;    // the box of its lit lights' positions
  float intensity;  // the sum of its lights' luminance lum(I) (Rec. 709, float)
  vec3 boundMax;
  uint lightIndex;  // a leaf's light in S0; kTreeNoLight for internal nodes and padding leaves
};
GPU_CHECK_SIZE(GpuLightTreeNode, 32);

// Uniforms of rtslc.comp (std140; one block per dispatch).
GPU_CONST uint kRtslcCuts = 0u;      // one invocation per block: its cut
GPU_CONST uint kRtslcSampling = 1u;  // one invocation per pixel: one light per cut node, one shadow ray each

// Scalars in groups of four (see gpu_prelude.h).
GPU_STRUCT(RtslcUniforms) {
  uint stage;      // kRtslc*
  uint leafCount;  // 2^(L-1): the first leaf's index
  uint cutSize;    // n: nodes per cut (1..kMaxCutNodes), one sample each per pixel (m = 1)
  uint blockSize;  // B: pixels per side of a block sharing a cut (1: per-pixel cuts)

  uint blocksPerRow;
  uint interleave;  // m: an m x m group of pixels splits each cut's nodes, x m^2 (1: none)
  uint frameSeed;
  uint ratioOutputs;  // 1: the ratio form's outputs are written too (the unshadowed sum, the ratio)

  float errorLimit;     // the error bound's distance floor, as a share of the lights' box diagonal
  float clampDistance;  // d_c of the light shading, as the LGH's
  float pad1, pad2;
};
GPU_CHECK_OFFSET(RtslcUniforms, blocksPerRow, 16);
GPU_CHECK_OFFSET(RtslcUniforms, errorLimit, 32);
GPU_CHECK_SIZE(RtslcUniforms, 48);

GPU_NAMESPACE_END
#endif
