#version 450 core
// Shades one grid light at the surface under this pixel: irradiance weighted by the light's blending
// function (DESIGN 4), added into the target. Albedo is applied at compositing, so interleaving and
// filtering work on smooth irradiance, not on textured radiance.
#include "shared/frame.glsl"
#include "shared/light_pass_types.h"
#include "shared/lgh_shading.glsl"

layout(std140, binding = LGH_UBO_PASS) uniform LightPass { LightPassUniforms pass; };
// The G-buffer in the target's layout (de-interleaved into tiles when interleaving).
layout(binding = 0) uniform sampler2D surfacePosition;
layout(binding = 1) uniform sampler2D surfaceNormal;
#ifdef LGH_COUNT_OVERDRAW
layout(r32ui, binding = 0) uniform coherent uimage2D fragmentCounts;
#endif

flat in vec3 lightPosition;
flat in vec3 lightIntensity;
flat in vec4 lightLobe;
flat in vec2 lightBlend;
flat in uint lightIndex;

layout(location = 0) out vec4 irradiance;  // rgb irradiance; a counts shaded fragments

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef LGH_COUNT_OVERDRAW
  imageAtomicAdd(fragmentCounts, pixel, 1u);  // every fragment rasterized, discarded or not
#endif
  vec4 position = texelFetch(surfacePosition, pixel, 0);
  if (position.w == 0.0) discard;  // background (or tile padding)
  float d = distance(lightPosition, position.xyz);
  float blend = blendWeight(uint(lightBlend.y), d, lightBlend.x);
  if (blend == 0.0) discard;
  vec3 n = texelFetch(surfaceNormal, pixel, 0).xyz;
  vec3 e = lightContribution(lightPosition, lightIntensity, lightLobe.xyz, lightLobe.w, position.xyz, n,
                             pass.alphaTopCellClampScale.z);
  irradiance = vec4(blend * e, 1.0);
}
