#version 450 core
// A max pyramid of the surfaces' culling depth (shared/light_levels.h) in the light pass's layout:
// level 0 from the positions, each further level the deepest of the finer texels it covers (three
// per axis at the odd end, so the last texel also covers a leftover row or column). Background
// counts as nearest (0): no light needs shading there. light_volume.vert skips a light whose whole
// rectangle only shows surfaces in front of its sphere (it is hidden behind them).
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.h"
#include "shared/frame.glsl"
#include "shared/light_levels.h"

layout(binding = LGH_TEXTURE_SURFACE_POSITION) uniform sampler2D surfacePosition;
layout(r32f, binding = LGH_IMAGE_PYRAMID_FINER) uniform readonly image2D finer;
layout(r32f, binding = LGH_IMAGE_PYRAMID_COARSER) uniform writeonly image2D coarser;
uniform int level;  // of `coarser`; 0: computed from surfacePosition
uniform float depthScale;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(coarser);
  if (any(greaterThanEqual(p, size))) return;
  float deepest = 0.0;
  if (level == 0) {
    vec4 position = texelFetch(surfacePosition, p, 0);
    if (position.w != 0.0) deepest = cullingDepth(clipW(frame.viewProjection, position.xyz), depthScale);
  } else {
    ivec2 finerSize = imageSize(finer);
    ivec2 span = ivec2(2) + ivec2(equal(p, size - 1)) * (finerSize & 1);
    for (int y = 0; y < span.y; ++y)
      for (int x = 0; x < span.x; ++x) deepest = max(deepest, imageLoad(finer, min(2 * p + ivec2(x, y), finerSize - 1)).r);
  }
  imageStore(coarser, p, vec4(deepest));
}
