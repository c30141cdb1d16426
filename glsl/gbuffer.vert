#version 450 core
// G-buffer: scene-space attributes of the visible surface.
#include "shared/frame.glsl"
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord0;
layout(location = 3) in vec2 inTexcoord1;
layout(location = 4) in vec4 inColor;
out vec3 worldPosition;
out vec3 worldNormal;
out vec4 texcoords;  // xy: TEXCOORD_0, zw: TEXCOORD_1
out vec4 vertexColor;
void main() {
  worldPosition = inPosition;  // the scene is flattened into scene space at load time
  worldNormal = inNormal;
  texcoords = vec4(inTexcoord0, inTexcoord1);
  vertexColor = inColor;
  // Camera-relative: the subtraction is exact for vertices near the camera, and the matrix holds no
  // large translation to round (render/camera_view.h).
  gl_Position = frame.cameraRelativeViewProjection * vec4(inPosition - frame.cameraPosition.xyz, 1.0);
}
