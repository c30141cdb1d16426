#version 450 core
// Splits the G-buffer's position and normal into n x n tiles: pixel (x, y) goes to tile
// (x mod n, y mod n) at (x div n, y div n) inside it. Each tile is a coarse image of the whole view,
// so a light drawn into one tile shades every n-th pixel of the full image.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"

layout(rgba32f, binding = LGH_IMAGE_TILED_POSITION) uniform writeonly image2D tiledPosition;
layout(rgba16f, binding = LGH_IMAGE_TILED_NORMAL) uniform writeonly image2D tiledNormal;
uniform uint tilesPerAxis;
uniform uvec2 tileSize;

void main() {
  uvec2 target = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(target, tilesPerAxis * tileSize))) return;
  uvec2 tile = target / tileSize, local = target % tileSize;
  ivec2 source = ivec2(local * tilesPerAxis + tile);
  bool inside = all(lessThan(source, ivec2(frame.resolution.xy)));
  // Padding past the image's edge reads as background (w = 0), which the light pass discards.
  vec4 position = inside ? texelFetch(gPosition, source, 0) : vec4(0.0);
  vec4 normal = inside ? texelFetch(gNormal, source, 0) : vec4(0.0);
  imageStore(tiledPosition, ivec2(target), position);
  imageStore(tiledNormal, ivec2(target), normal);
}
