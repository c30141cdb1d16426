#version 450 core
// Puts the n x n tiles of the interleaved light pass back together and removes the interleaving
// pattern: every pixel averages its neighbours over the interleaving window (shared/interleave_window.glsl:
// n x n, each tile counted once), weighted by how much each neighbour's surface looks like its own. Each
// tile's value was scaled by n^2 in the light pass, so on a smooth surface the average is the sum over all
// tiles: all lights.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/interleave_window.glsl"

layout(binding = LGH_TEXTURE_TILED_IRRADIANCE) uniform sampler2D tiledIrradiance;          // rgb irradiance x n^2, a shaded fragments
layout(binding = LGH_TEXTURE_TILED_FRAGMENT_COUNTS) uniform usampler2D tiledFragmentCounts;     // when countFragments != 0
layout(rgba32f, binding = LGH_IMAGE_RESOLVED_IRRADIANCE) uniform writeonly image2D irradianceOut;
layout(r32ui, binding = LGH_IMAGE_RESOLVED_FRAGMENT_COUNTS) uniform writeonly uimage2D fragmentCountsOut;
uniform uint tilesPerAxis;
uniform uvec2 tileSize;
uniform int countFragments;
uniform float normalPower;    // normal weight: max(0, n_p . n_q)^normalPower
uniform float planeSigma;     // plane-distance weight: sigma in pixel footprints at the pixel's depth

ivec2 tiledCoord(ivec2 pixel) {
  uvec2 p = uvec2(pixel);
  return ivec2((p % tilesPerAxis) * tileSize + p / tilesPerAxis);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.resolution.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  ivec2 own = tiledCoord(pixel);
  if (countFragments != 0) imageStore(fragmentCountsOut, pixel, texelFetch(tiledFragmentCounts, own, 0));
  float shadedFragments = texelFetch(tiledIrradiance, own, 0).a;
  Surface s = loadSurface(pixel);
  if (!s.valid || tilesPerAxis == 1u) {
    imageStore(irradianceOut, pixel, vec4(s.valid ? texelFetch(tiledIrradiance, own, 0).rgb : vec3(0.0), shadedFragments));
    return;
  }
  ivec2 halfWidths = interleaveHalfWidths(tilesPerAxis, 1.0);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int dy = -halfWidths.y; dy <= halfWidths.y; ++dy) {
    for (int dx = -halfWidths.x; dx <= halfWidths.x; ++dx) {
      float w = interleaveTapWeight(s, pixel, ivec2(dx, dy), tilesPerAxis, halfWidths, normalPower, planeSigma);
      if (w > 0.0) sum += w * texelFetch(tiledIrradiance, tiledCoord(pixel + ivec2(dx, dy)), 0).rgb;
      weightSum += w;
    }
  }
  // The pixel's own sample has weight 1, so weightSum never vanishes on a valid pixel.
  imageStore(irradianceOut, pixel, vec4(sum / weightSum, shadedFragments));
}
