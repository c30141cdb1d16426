// Uniforms of the light-volume pass (one block, std140), shared by light_volume.vert/.frag and C++.
#ifndef LGH_LIGHT_PASS_TYPES_H
#define LGH_LIGHT_PASS_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kMaxLightPassLevels = 16u;
GPU_CONST uint kMaxShadowSamples = 16u;
GPU_CONST uint kMaxShadowTargets = 32u;  // input lights drawn per grid light per frame (shadow_targets.comp): 2k
GPU_CONST uint kMaxInterleave = 8u;      // n x n interleaved sampling: n <= 8

GPU_CONST uint kSelectSkipFinest = 1u;  // the finest level blended takes no part (the paper skips S1)
GPU_CONST uint kSelectUniform = 2u;     // every contributing light equally likely (for comparison)
// Counting the grid lights a pixel cannot select (light_volume.frag, LGH_COUNT_UNSELECTABLE), each drawn
// light blended by its own distance (shadow-blend-targets), not by its grid light's centre's.
GPU_CONST uint kSelectBlendTargets = 4u;

// A selected light in a shadow slot: bit 31 set for an S0 light (index into the input lights),
// clear for a grid light (index into the merged grid-light buffer). kNoLight: slot still empty.
GPU_CONST uint kSlotS0 = 0x80000000u;
GPU_CONST uint kNoLight = 0xffffffffu;

// How a light volume is drawn (LightPassUniforms::volumeShape).
GPU_CONST uint kVolumeFullScreen = 0u;  // a full-screen triangle (top level, brute force)
GPU_CONST uint kVolumeCube = 1u;        // the paper's cube of half-size 2R, no depth test
GPU_CONST uint kVolumeCulled = 2u;      // the screen octagon of the 2R sphere, depth- and stencil-tested

// Scalars in groups of four (std140 and C++ agree without padding; see gpu_prelude.h).
GPU_STRUCT(LightPassUniforms) {
  float alpha;              // R_l = alpha h_l
  float topCellSize;        // H
  float clampDistance;      // d_c
  float contributionScale;  // n^2 with n x n interleaving (each light shades 1/n^2 of the pixels)

  uint firstLevel;      // finest level blended: 0 (S0) or 1 (S1)
  uint levels;          // L
  uint instanceOffset;  // index of this draw's first light in the bound buffer
  uint volumeShape;     // kVolume*

  uint tilesPerAxis;  // n
  uint tileWidth;
  uint tileHeight;
  uint boundLightOffset;  // global index of the bound buffer's first light (S0 is bound in chunks;
                          // tiles are dealt by global index)

  uint imageWidth;  // full resolution
  uint imageHeight;
  uint bruteForce;          // 1: weight 1 for every light
  float cullingDepthScale;  // cullingDepth()'s scale, as the depth target was written with

  // Shadow-sample selection (docs/design.md §5)
  uint shadowSamples;  // k slots per pixel (0 = off)
  uint selectFlags;    // kSelect*
  uint frameSeed;
  uint tileRotation;  // added to a light's index before dealing it to a tile: rotated per frame
                      // while accumulating, so n^2 frames give every pixel every light once

  float defensive;    // a grid light's selection importance adds defensive x its cosine-free contribution
  uint drawnTargets;  // m input lights drawn per grid light this frame (ShadowTargets), read when the
                      // unselectable grid lights are counted
  uint pad0, pad1;

  // levelOffsets[l / 4][l % 4]: index of level l's first light in the merged grid-light buffer
  // (S0: 0), for dealing each level's lights evenly to the tiles
  uvec4 levelOffsets[kMaxLightPassLevels / 4u];
};
GPU_CHECK_OFFSET(LightPassUniforms, firstLevel, 16);
GPU_CHECK_OFFSET(LightPassUniforms, tilesPerAxis, 32);
GPU_CHECK_OFFSET(LightPassUniforms, imageWidth, 48);
GPU_CHECK_OFFSET(LightPassUniforms, shadowSamples, 64);
GPU_CHECK_OFFSET(LightPassUniforms, defensive, 80);
GPU_CHECK_OFFSET(LightPassUniforms, drawnTargets, 84);
GPU_CHECK_OFFSET(LightPassUniforms, levelOffsets, 96);
GPU_CHECK_SIZE(LightPassUniforms, 160);

GPU_NAMESPACE_END
#endif
