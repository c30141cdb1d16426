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
flat in vec3 lightVariance;

// The light this fragment shades, as lightSelection reads it.
ShadedLight shadedLight() {
  ShadedLight l;
  l.position = lightPosition;
  l.omniFraction = lightLobe.w;
  l.intensity = lightIntensity;
  l.level = 0u;  // not read
  l.meanNormal = lightLobe.xyz;
  l.pad = 0.0;
  return l;
}

#ifdef LGH_COUNT_UNSELECTABLE
// This frame's drawn lights of every grid light (ShadowTargets: pass.drawnTargets per grid light) and the
// input lights they index. (A variant of its own: llvmpipe runs both sides of a branch under a mask, so
// this code would cost every fragment whether or not the counting is on.)
layout(std430, binding = LGH_BINDING_PASS4) readonly buffer DrawnTargets { uint drawnTargets[]; };
layout(std430, binding = LGH_BINDING_PASS5) readonly buffer InputLights { GpuLight inputLights[]; };

// A grid light whose volume covers x but which the selection cannot pick here, its centre in the level's
// fade-in hole (blend 0) or behind x's tangent plane (contribution 0), may still hold input lights that
// light x: a light beyond the hole's edge has B_l > 0 at its own distance, one above the plane faces x.
// The samples' estimate of what the input lights add, F' mean(w) (shadow_rays.comp), blends each light by
// its own distance, so it counts every input light fully only if every grid light holding it is
// selectable; without the others the sum falls short and the corrected image comes out the darker the
// more it trusts it (docs/design.md §5, "Counting the unselectable grid lights"). So one of the grid
// light's drawn lights r, drawn by its share, adds a_g B_l(|x - p_r|) G_r(x), an unbiased estimate of what
// its lights add here, to the pixel's unselectable total U, which T adds. No sample is spent on them:
// their light takes the pixel's visibility ratio. Skipped where the lights within two standard deviations
// of the centre cannot light x either (all in the hole, all behind the plane, or all facing away).
void countUnselectable(uint pixelIndex, vec3 x, vec3 n, float d, uint role, float R, float centreBlend) {
  vec3 variance = lightVariance;
  if (centreBlend == 0.0 && d + 2.0 * sqrt(variance.x + variance.y + variance.z) <= 0.5 * R) return;
  if (dot(n, lightPosition - x) <= -2.0 * sqrt(dot(n * n, variance))) return;
  vec3 m = lightLobe.xyz;  // one-sided (|m| = 1: every light's normal is m; no omni share)
  bool oneSided = lightLobe.w < 1e-3 && length(m) > 1.0 - 1e-3;
  if (oneSided && dot(m, x - lightPosition) <= -2.0 * sqrt(dot(m * m, variance))) return;
  Rng rng = makeRng(lightId * 0x85ebca6bu ^ pixelIndex, pass.frameSeed ^ 0xc2b2ae35u);
  uint race = min(uint(nextFloat(rng) * float(pass.drawnTargets)), pass.drawnTargets - 1u);
  uint drawn = drawnTargets[lightId * pass.drawnTargets + race];
  if (drawn == kNoLight) return;
  ShadedLight l = decodeInputLight(inputLights[drawn]);
  float blend =
      (pass.selectFlags & kSelectBlendTargets) != 0u ? blendWeight(role, distance(l.position, x), R) : centreBlend;
  float added = blend * luminance(lightIntensity) * geometricFactor(l, x, n, pass.clampDistance);
  if (added > 0.0) addUnselectable(pixelIndex, added);
}
#endif

layout(location = 0) out vec4 irradiance;  // rgb irradiance; a counts shaded fragments

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef LGH_COUNT_OVERDRAW
  imageAtomicAdd(fragmentCounts, pixel, 1u);  // every fragment rasterized, discarded or not
#endif
  vec4 position = texelFetch(surfacePosition, pixel, 0);
  if (position.w == 0.0) discard;  // background (or tile padding)
  float d = distance(lightPosition, position.xyz);
  uint role = uint(lightBlend.y);
  float R = lightBlend.x;
  float blend = blendWeight(role, d, R);
#ifdef LGH_COUNT_UNSELECTABLE
  // In a fade-in hole the grid light adds nothing here, but its lights beyond the hole's edge may: counted below.
  bool inHole = (role == kRoleMiddle || role == kRoleTop) && d <= 0.5 * R;
  if (blend == 0.0 && !inHole) discard;
#else
  if (blend == 0.0) discard;
#endif
  vec3 n = texelFetch(surfaceNormal, pixel, 0).xyz;
  bool gridLight = (lightId & kSlotS0) == 0u;
  LightSelection lit = lightSelection(shadedLight(), position.xyz, n, d, blend, gridLight, pass.clampDistance,
                                      pass.defensive, (pass.selectFlags & kSelectUniform) != 0u);
  irradiance = vec4(lit.irradiance, 1.0);
#ifdef LGH_SELECT_SHADOWS
  bool finest = role == kRoleFinest;
  if (!(finest && (pass.selectFlags & kSelectSkipFinest) != 0u)) {
    uint pixelIndex = uint(pixel.y) * (pass.tilesPerAxis * pass.tileWidth) + uint(pixel.x);
    if (lit.importance > 0.0)
      selectShadowSample(pixelIndex, lightId, lit.importance, pass.shadowSamples, pass.frameSeed);
#ifdef LGH_COUNT_UNSELECTABLE
    else
      countUnselectable(pixelIndex, position.xyz, n, d, role, R, blend);
#endif
  }
#endif
#ifdef LGH_COUNT_UNSELECTABLE
  if (blend == 0.0) discard;  // in the hole: counted, nothing to add to the irradiance
#endif
}
