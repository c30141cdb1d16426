#version 450 core
// One grid light per instance, drawn as a cube of half-size 2R (the support of its blending function)
// or, for the top level and brute force, as a full-screen triangle. With n x n interleaving the light
// is drawn into one tile only: its clip-space position is mapped into that tile's block of the
// de-interleaved target and clipped to it with four clip distances.
#include "shared/frame.glsl"
#include "shared/light_pass_types.h"
#include "shared/lgh_shading.glsl"
#include "shared/lgh_types.h"
#include "shared/octahedral.h"

layout(std140, binding = LGH_UBO_PASS) uniform LightPass { LightPassUniforms pass; };
#ifdef LGH_S0_INPUT
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight lights[]; };
#else
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer GridLights { GpuGridLight lights[]; };
#endif

out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[4];
};
flat out vec3 lightPosition;
flat out vec3 lightIntensity;
flat out vec4 lightLobe;    // xyz mean normal, w omni fraction
flat out vec2 lightBlend;   // x: R, y: role
flat out uint lightId;      // for shadow-sample selection: kSlotS0 | S0 index, or grid-light index

// 12 triangles of the unit cube [-1,1]^3, counter-clockwise seen from outside: culling front faces
// leaves exactly one (back) face under every covered pixel, also with the camera inside the cube.
const uint kCubeIndices[36] = uint[](0u, 2u, 1u, 1u, 2u, 3u, 4u, 5u, 6u, 5u, 7u, 6u, 0u, 1u, 4u, 1u, 5u, 4u,
                                     2u, 6u, 3u, 3u, 6u, 7u, 0u, 4u, 2u, 2u, 4u, 6u, 1u, 3u, 5u, 3u, 7u, 5u);

uint levelOf(uint index) {
#ifdef LGH_S0_INPUT
  return 0u;
#else
  return lights[index].level;
#endif
}

void main() {
  uint index = pass.levels.z + uint(gl_InstanceID);
  uint level = levelOf(index);
#ifdef LGH_S0_INPUT
  lightId = kSlotS0 | (index + pass.tiles.w);
  GpuLight l = lights[index];
  lightPosition = l.position;
  lightIntensity = l.intensity;
  bool oriented = (l.flags & kLightOriented) != 0u;
  lightLobe = oriented ? vec4(octDecode(l.normalOct), 0.0) : vec4(0.0, 0.0, 0.0, 1.0);
#else
  lightId = index;
  GpuGridLight l = lights[index];
  lightPosition = l.position;
  lightIntensity = l.intensity;
  lightLobe = vec4(l.meanNormal, l.omniFraction);
#endif
  lightIntensity *= pass.alphaTopCellClampScale.w;
  // R_l = alpha h_l, h_l = H 2^(l - L); h_0 = h_1 / 2 by the same formula.
  float R = pass.alphaTopCellClampScale.x * pass.alphaTopCellClampScale.y *
            exp2(float(int(level) - int(pass.levels.y)));
  uint role = pass.image.z != 0u ? kRoleOnly : levelRole(level, pass.levels.x, pass.levels.y);
  lightBlend = vec2(R, float(role));

  vec4 clip;
  if (pass.levels.w != 0u) {
    // Full-screen triangle covering the viewport.
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    clip = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
  } else {
    uint c = kCubeIndices[gl_VertexID];
    vec3 corner = vec3(float(c & 1u), float((c >> 1u) & 1u), float((c >> 2u) & 1u)) * 2.0 - 1.0;
    clip = frame.viewProjection * vec4(lightPosition + 2.0 * R * corner, 1.0);
    clip.z = 0.0;  // no depth test; never clipped by near/far as long as w > 0
  }

  // Interleaving: this light belongs to tile (k mod n^2) of its level, k its index within the level.
  uint n = pass.tiles.x;
  uint levelStart = pass.levelOffsets[level / 4u][level % 4u];
  uint tile = (index + pass.tiles.w - levelStart) % (n * n);
  vec2 t = vec2(float(tile % n), float(tile / n));
  vec2 tileSize = vec2(pass.tiles.yz), full = vec2(pass.image.xy);
  // Full-resolution window x maps to tile-local x' = (x - t - 0.5) / n + 0.5, placed at t * tileSize.
  vec2 a = full / (float(n * n) * tileSize);
  vec2 b = 2.0 * (t * tileSize + (0.5 * full - t - 0.5) / float(n) + 0.5) / (float(n) * tileSize) - 1.0;
  vec4 tiled = vec4(a * clip.xy + b * clip.w, clip.z, clip.w);
  vec2 lo = 2.0 * t / float(n) - 1.0, hi = 2.0 * (t + 1.0) / float(n) - 1.0;
  gl_ClipDistance[0] = tiled.x - lo.x * tiled.w;
  gl_ClipDistance[1] = hi.x * tiled.w - tiled.x;
  gl_ClipDistance[2] = tiled.y - lo.y * tiled.w;
  gl_ClipDistance[3] = hi.y * tiled.w - tiled.y;
  gl_Position = tiled;
}
