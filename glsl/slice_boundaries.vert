#version 450 core
// Instance j (from 1) of a full-screen triangle at the volumeDepth of slice boundary j (a culling depth,
// sliceBoundary): drawn with depth test GEQUAL (the boundary at or before the surface) and stencil op
// INCR, each pixel's stencil ends as sliceOf(its surface's culling depth) (shared/light_levels.h). The
// boundary is moved a little towards the camera: a rounding may count one boundary too many (a pixel
// seen farther, culled less), never one too few. GL_ZERO_TO_ONE; no colour is written.
#include "shared/frame.glsl"
#include "shared/light_levels.h"
uniform uint slices;
uniform float depthScale;
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  float w = cullingDepthW(sliceBoundary(uint(gl_InstanceID) + 1u, slices), depthScale);
  float depth = min(volumeDepth(w, frame.sceneScale.w) * (1.0 + 1e-5), 1.0);
  gl_Position = vec4(corner * 2.0 - 1.0, depth, 1.0);
}
