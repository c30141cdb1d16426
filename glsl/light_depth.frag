#version 450 core
// The depth the light pass culls against (shared/light_levels.h, cullingDepth): each surface's clip w,
// read from its position in the light pass's own layout (de-interleaved tiles when interleaving), so
// the test neither depends on the G-buffer's depth convention nor on how the tiles were split.
// Background and tile padding get the far end: no light volume is shaded there.
#include "shared/frame.glsl"
#include "shared/light_levels.h"

layout(binding = 0) uniform sampler2D surfacePosition;
uniform float depthScale;

void main() {
  vec4 position = texelFetch(surfacePosition, ivec2(gl_FragCoord.xy), 0);
  if (position.w == 0.0) {
    gl_FragDepth = 1.0;
    return;
  }
  gl_FragDepth = cullingDepth(clipW(frame.viewProjection, position.xyz), depthScale);
}
