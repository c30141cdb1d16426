#version 450 core
// One grid light per point, at its illumination centre. A point the visible surface hides (the
// G-buffer's surface at its pixel is clearly nearer the camera) is drawn faint rather than dropped,
// so the whole level stays readable.
#include "shared/bindings.h"
#include "shared/lgh_types.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer GridLights { GpuGridLight lights[]; };
layout(binding = LGH_TEXTURE_SURFACE_POSITION) uniform sampler2D surfacePosition;  // xyz world position, w = 1 on geometry
uniform mat4 viewProjection;
uniform vec3 cameraPosition;
uniform uint firstLight;  // the level's offset in the merged buffer
uniform float pointSize;  // pixels

flat out vec4 pointColor;

void main() {
  GpuGridLight l = lights[firstLight + uint(gl_VertexID)];
  vec4 clip = viewProjection * vec4(l.position, 1.0);
  gl_Position = clip;
  gl_PointSize = pointSize;
  float alpha = 1.0;
  if (clip.w > 0.0) {
    ivec2 size = textureSize(surfacePosition, 0);
    ivec2 pixel = ivec2((clip.xy / clip.w * 0.5 + 0.5) * vec2(size));
    if (all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, size))) {
      vec4 surface = texelFetch(surfacePosition, pixel, 0);
      // Clusters of VPLs sit on or near surfaces: only a light well behind the surface counts as hidden.
      float toLight = distance(cameraPosition, l.position);
      if (surface.w > 0.0 && toLight > 1.02 * distance(cameraPosition, surface.xyz)) alpha = 0.25;
    }
  }
  pointColor = vec4(0.25, 0.95, 1.0, alpha);  // cyan: stands out on the warm and grey scenes we render
}
