#version 450 core
#if defined(LGH_SELECT_SHADOWS) && !defined(LGH_SELECTION_NO_ATOMICS)
#extension GL_NV_shader_atomic_float : require
#endif
// Shades one grid light at the surface under this pixel: irradiance weighted by the light's blending
// function (docs/design.md §4), added into the target. Albedo is applied at compositing, so interleaving and
// filtering work on smooth irradiance, not on textured radiance.
#include "shared/bindings.h"
#include "shared/color.glsl"
#include "shared/frame.glsl"
#include "shared/lgh_shading.glsl"
#include "shared/light_pass_types.h"
#ifdef LGH_SELECT_SHADOWS
#include "shared/shadow_selection.glsl"
#endif

#ifdef LGH_DEPTH_CULLED
// The depth test runs before the shader, so fragments over surfaces behind the volume are never
// shaded nor counted (the counter below is a side effect, which would otherwise force late tests).
layout(early_fragment_tests) in;
#endif

layout(std140, binding = LGH_UBO_PASS) uniform LightPass { LightPassUniforms pass; };
// The G-buffer in the target's layout (de-interleaved into tiles when interleaving).
layout(binding = LGH_TEXTURE_SURFACE_POSITION) uniform sampler2D surfacePosition;
layout(binding = LGH_TEXTURE_SURFACE_NORMAL) uniform sampler2D surfaceNormal;
#ifdef LGH_COUNT_OVERDRAW
layout(r32ui, binding = LGH_IMAGE_FRAGMENT_COUNTS) uniform coherent uimage2D fragmentCounts;
#endif

flat in vec3 lightPosition;
flat in vec3 lightIntensity;
flat in vec4 lightLobe;
flat in vec2 lightBlend;
flat in uint lightId;  // kSlotS0 | S0 index, or merged grid-light index

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
  vec3 e =
      lightContribution(lightPosition, lightIntensity, lightLobe.xyz, lightLobe.w, position.xyz, n, pass.clampDistance);
  irradiance = vec4(blend * e, 1.0);
#ifdef LGH_SELECT_SHADOWS
  bool finest = uint(lightBlend.y) == kRoleFinest;
  if (!(finest && (pass.selectFlags & kSelectSkipFinest) != 0u)) {
    bool gridLight = (lightId & kSlotS0) == 0u;
    float importance = selectionImportance(irradiance.rgb, lightIntensity, blend, d, pass.clampDistance,
                                           gridLight ? pass.defensive : 0.0);
    if ((pass.selectFlags & kSelectUniform) != 0u && importance > 0.0) importance = 1.0;
    uint pixelIndex = uint(pixel.y) * (pass.tilesPerAxis * pass.tileWidth) + uint(pixel.x);
    selectShadowSample(pixelIndex, lightId, importance, pass.shadowSamples, pass.frameSeed);
  }
#endif
}
