#version 450 core
// Puts the n x n tiles of the interleaved light pass back together and removes the interleaving
// pattern: every pixel averages an n x n window of its neighbours (a box of width n with half-weight
// ends, n + 1 taps per axis, so each tile is counted exactly once and the window is symmetric),
// weighted by how much each neighbour's surface looks like its own. Each tile's value was scaled by
// n^2 in the light pass, so on a smooth surface the average is the sum over all tiles: all lights.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"

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
  // A neighbour's distance from this pixel's tangent plane, in units of the pixel footprint here.
  float footprint = max(distance(frame.cameraPosition.xyz, s.position) * frame.sceneScale.z, 1e-30);
  int half_ = int(tilesPerAxis / 2u);
  bool even = (tilesPerAxis & 1u) == 0u;
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int dy = -half_; dy <= half_; ++dy) {
    for (int dx = -half_; dx <= half_; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 qPosition = texelFetch(gPosition, q, 0);
      if (qPosition.w == 0.0) continue;
      float window = (even && abs(dx) == half_ ? 0.5 : 1.0) * (even && abs(dy) == half_ ? 0.5 : 1.0);
      vec3 qNormal = texelFetch(gNormal, q, 0).xyz;
      float plane = abs(dot(s.normal, qPosition.xyz - s.position)) / (footprint * planeSigma);
      float w = window * pow(max(0.0, dot(s.normal, qNormal)), normalPower) * exp(-0.5 * plane * plane);
      sum += w * texelFetch(tiledIrradiance, tiledCoord(q), 0).rgb;
      weightSum += w;
    }
  }
  // The pixel's own sample has weight >= 1/4 > 0, so weightSum never vanishes on a valid pixel.
  imageStore(irradianceOut, pixel, vec4(sum / weightSum, shadedFragments));
}
