#version 450 core
// G-buffer: world-space attributes of the visible surface.
#include "shared/frame.glsl"
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
out vec3 worldPosition;
out vec3 worldNormal;
out vec2 texcoord;
void main() {
  worldPosition = inPosition;  // the scene is flattened into world space at load time
  worldNormal = inNormal;
  texcoord = inTexcoord;
  gl_Position = frame.viewProjection * vec4(inPosition, 1.0);
}
