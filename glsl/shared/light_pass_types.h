// Uniforms of the light-volume pass (one block, std140), shared by light_volume.vert/.frag and C++.
#ifndef LGH_LIGHT_PASS_TYPES_H
#define LGH_LIGHT_PASS_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kMaxLightPassLevels = 16u;

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
  // levelOffsets[l]: index of level l's first light in the merged grid-light buffer (S0: 0), for
  // spreading each level's lights evenly over the tiles
  uvec4 levelOffsets[kMaxLightPassLevels / 4u];
};
GPU_CHECK_SIZE(LightPassUniforms, 128);

GPU_NAMESPACE_END
#endif
