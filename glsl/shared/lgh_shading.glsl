// The LGH shading model in GLSL: blending functions (lgh/blending.h) and the contribution of one
// light (lgh/shading.h). The C++ versions are the reference; tests/render/lgh_shading_test.cpp runs
// these on the GPU against them on the same inputs.
#ifndef LGH_LGH_SHADING_GLSL
#define LGH_LGH_SHADING_GLSL

#include "shared/color.glsl"      // luminance()
#include "shared/light_levels.h"  // roles (kRole*, levelRole) and R_l, shared with C++

// Weight of a light of a level with the given role at distance d, R = alpha * h_level.
float blendWeight(uint role, float d, float R) {
  if (role == kRoleOnly) return 1.0;
  bool fadesIn = role == kRoleMiddle || role == kRoleTop;
  bool fadesOut = role == kRoleFinest || role == kRoleMiddle;
  if (d <= 0.5 * R) return fadesIn ? 0.0 : 1.0;
  if (d <= R) return fadesIn ? 2.0 * d / R - 1.0 : 1.0;
  if (d < 2.0 * R) return fadesOut ? 2.0 - d / R : 1.0;
  return fadesOut ? 0.0 : 1.0;
}

// Flux-conserving emission lobe of a cluster (see lgh/shading.h for the derivation).
float emissionLobe(vec3 meanNormal, float omniFraction, vec3 u) {
  return max(0.0, max(0.0, dot(meanNormal, u)) + (1.0 - length(meanNormal) - omniFraction) * 0.25 + omniFraction);
}

const float kMinDistanceSq = 1e-24;

// I * max(0, n.w) * F(-w) / max(d^2, dc^2): irradiance at x (multiply by rho/pi for radiance).
vec3 lightContribution(vec3 lightPos, vec3 intensity, vec3 meanNormal, float omniFraction, vec3 x, vec3 n,
                       float clampDistance) {
  vec3 toLight = lightPos - x;
  float d = length(toLight);
  vec3 w = d > 0.0 ? toLight / d : n;
  float cosine = max(0.0, dot(n, w));
  if (cosine == 0.0) return vec3(0.0);
  float distanceSq = max(max(d * d, clampDistance * clampDistance), kMinDistanceSq);
  return intensity * (cosine * emissionLobe(meanNormal, omniFraction, -w) / distanceSq);
}

// What light `light` adds at x per unit of its luminance: cosine, emission lobe, clamped 1 / d^2 (the
// geometric factor G of docs/design.md §5; 0 for a light without luminance).
float geometricFactor(ShadedLight light, vec3 x, vec3 n, float clampDistance) {
  float a = luminance(light.intensity);
  if (!(a > 0.0)) return 0.0;
  return luminance(lightContribution(light.position, light.intensity, light.meanNormal, light.omniFraction, x, n,
                                     clampDistance)) /
         a;
}

// What a light adds at the surface (x, n), blended, and the shadow-sample selection's importance c'_l of it
// there (docs/design.md §5). The light pass draws a pixel's k lights in proportion to c'_l
// (light_volume.frag) and the shadow rays weigh each sample by what its light adds over c'_l
// (shadow_rays.comp): the weights are right only if both compute it alike, so both call lightSelection.
struct LightSelection {
  vec3 irradiance;   // B_l(d) x the light's contribution at x (W/m^2)
  float importance;  // c'_l
};

// d = |p_l - x|, blend = B_l(d). c'_l is the blended contribution's luminance plus, for a grid light,
// `defensive` x what it would add without the cosines at x and at the light ("Defensive selection"): a
// grid light stands for input lights spread over its cell and beyond; where its centre grazes x or faces
// away, its own contribution is small or zero while its lights' is not, so a sample weighed by their
// quotient would be heavy-tailed (or those lights never sampled). The cosine-free term bounds the
// quotient (defensive importance sampling, Hesterberg 1995). uniformSelection: every light that
// contributes has importance 1 (the paper's comparison).
LightSelection lightSelection(ShadedLight light, vec3 x, vec3 n, float d, float blend, bool gridLight,
                              float clampDistance, float defensive, bool uniformSelection) {
  LightSelection s;
  s.irradiance = blend * lightContribution(light.position, light.intensity, light.meanNormal, light.omniFraction, x,
                                           n, clampDistance);
  s.importance = luminance(s.irradiance);
  if (gridLight && defensive > 0.0)  // off by default: the light pass's hot loop skips the term
    s.importance +=
        defensive * blend * luminance(light.intensity) / max(max(d * d, clampDistance * clampDistance), kMinDistanceSq);
  if (uniformSelection && s.importance > 0.0) s.importance = 1.0;
  return s;
}

#endif
