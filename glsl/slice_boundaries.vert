#version 450 core
// Instance j (from 1) of a full-screen triangle at culling depth sliceBoundary(j): drawn with depth
// test LEQUAL and stencil op INCR, each pixel's stencil ends as sliceOf(its surface's depth)
// (shared/light_levels.h). No colour is written.
#include "shared/light_levels.h"
uniform uint slices;
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  float depth = sliceBoundary(uint(gl_InstanceID) + 1u, slices);
  gl_Position = vec4(corner * 2.0 - 1.0, 2.0 * depth - 1.0, 1.0);
}
