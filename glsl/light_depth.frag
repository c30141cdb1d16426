#version 450 core
#ifdef LGH_STENCIL_EXPORT
#extension GL_ARB_shader_stencil_export : require
#endif
// The depth the light pass culls against (shared/light_levels.h, volumeDepth of each surface's clip w),
// read from its position in the light pass's own layout (de-interleaved tiles when interleaving), so
// the test neither depends on the G-buffer's depth convention nor on how the tiles were split.
// Background and tile padding get the far end (0): no light volume is shaded there. With stencil export
// the surface's depth slice (sliceOf its cullingDepth) goes to the stencil in the same pass (else
// VolumeCulling counts it with one draw per slice boundary).
#include "shared/bindings.h"
#include "shared/frame.glsl"
#include "shared/light_levels.h"

layout(binding = LGH_TEXTURE_SURFACE_POSITION) uniform sampler2D surfacePosition;
uniform float depthScale;
uniform uint slices;

void main() {
  vec4 position = texelFetch(surfacePosition, ivec2(gl_FragCoord.xy), 0);
  float w = clipW(frame.viewProjection, position.xyz);
  bool background = position.w == 0.0;
  gl_FragDepth = background ? 0.0 : volumeDepth(w, frame.sceneScale.w);
#ifdef LGH_STENCIL_EXPORT
  gl_FragStencilRefARB = int(sliceOf(background ? 1.0 : cullingDepth(w, depthScale), slices));
#endif
}
