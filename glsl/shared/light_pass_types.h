// Uniforms of the light-volume pass (one block, std140), shared by light_volume.vert/.frag and C++.
#ifndef LGH_LIGHT_PASS_TYPES_H
#define LGH_LIGHT_PASS_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kMaxLightPassLevels = 16u;
GPU_CONST uint kMaxShadowSamples = 16u;
GPU_CONST uint kMaxInterleave = 8u;  // n x n interleaved sampling: n <= 8

GPU_CONST uint kSelectSkipFinest = 1u;  // the finest level blended takes no part (the paper skips S1)
GPU_CONST uint kSelectUniform = 2u;     // every contributing light equally likely (for comparison)

// A selected light in a shadow slot: bit 31 set for an S0 light (index into the input lights),
// clear for a grid light (index into the merged grid-light buffer). kNoLight: slot still empty.
GPU_CONST uint kSlotS0 = 0x80000000u;
GPU_CONST uint kNoLight = 0xffffffffu;

GPU_STRUCT(LightPassUniforms) {
  // x: alpha, y: H (top cell size), z: clamp distance d_c, w: contribution scale (n^2 with interleaving)
  vec4 alphaTopCellClampScale;
  // x: first level drawn (0 = S0), y: L, z: instance offset of this draw, w: 1 = full-screen draw
  uvec4 levels;
  // x: n (tiles per axis), y: tile width, z: tile height, w: global index of the bound buffer's first
  // light (S0 is drawn in chunks of one storage block each; tiles are assigned by global index)
  uvec4 tiles;
  // x, y: full-resolution image size; z: 1 = brute force (weight 1 for every light), w: 0
  uvec4 image;
  // Shadow-sample selection (DESIGN 5). x: k slots per pixel (0 = off), y: kSelect* flags,
  // z: frame seed, w: 0
  uvec4 selection;
  // levelOffsets[l]: index of level l's first light in the merged grid-light buffer (S0: 0), for
  // spreading each level's lights evenly over the tiles
  uvec4 levelOffsets[kMaxLightPassLevels / 4u];
};
GPU_CHECK_SIZE(LightPassUniforms, 144);

GPU_NAMESPACE_END
#endif
