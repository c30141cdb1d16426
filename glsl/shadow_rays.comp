#version 450 core
// One shadow ray per selected light per pixel (docs/design.md §5): from the pixel's surface to the light,
// any-hit through the scene BVH. A selected grid light is reached through one of its input lights,
// drawn by its share of the grid light's importance (shadow_targets.comp), or, as in the paper,
// through its centre jittered by the cluster's spread (when no targets were drawn). Writes the raw visibility ratio:
// the mean of the k visibilities (importance selection, each sample already drawn in proportion to its contribution),
// weighted by what the grid light's drawn lights add over what its centre adds (weighTargets), or the
// contribution-weighted mean (uniform selection); and the samples' mean weight (blue).
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.h"
#include "shared/bvh_traverse.glsl"
#include "shared/color.glsl"
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/lgh_shading.glsl"
#include "shared/lgh_types.h"
#include "shared/light_levels.h"
#include "shared/light_pass_types.h"
#include "shared/octahedral.h"
#include "shared/ray_offset.h"
#include "shared/sampling.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight inputLights[]; };
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer ShadowSlots { uint shadowSlots[]; };
layout(std430, binding = LGH_BINDING_PASS3) readonly buffer GridLights { GpuGridLight gridLights[]; };
layout(std430, binding = LGH_BINDING_PASS4) readonly buffer Targets { uint clusterTargets[]; };
layout(rgba32f,
       binding = LGH_IMAGE_SHADOW_RATIO) uniform writeonly image2D ratioOut;  // r: visibility ratio, g: rays traced

uniform uint samples;       // k
uniform uint tilesPerAxis;  // the slots are in the light pass's (tiled) layout
uniform uvec2 tileSize;
uniform uint races;           // input lights drawn per grid light (ShadowTargets); 0: jittered centres
uniform int resampleTargets;  // pick among a grid light's drawn lights by their geometric factor here
uniform int weighTargets;     // weigh each grid light's visibility by its drawn lights' G over its centre's
uniform float spread;         // jitter scale: the jitter's standard deviation is spread x the cluster's
uniform int uniformSelection;
uniform float clampDistance;
// For uniform selection's weights: the blending parameters of the light pass.
uniform float alpha;
uniform float topCellSize;
uniform uint firstLevel;
uniform uint levels;
uniform int bruteForce;
uniform uint frameSeed;

// Raised-cosine variate on [-1, 1], pdf (1 + cos(pi s)) / 2, by Newton's method on its CDF
// (s + 1) / 2 + sin(pi s) / (2 pi); four steps from a good start reach float precision.
float raisedCosine(float u) {
  float s = 2.0 * u - 1.0;
  s = sign(s) * (1.0 - sqrt(1.0 - abs(s)));  // the CDF's shape near the ends
  for (int i = 0; i < 4; ++i) {
    float f = 0.5 * (s + 1.0) + sin(kPi * s) / (2.0 * kPi) - u;
    float df = 0.5 * (1.0 + cos(kPi * s));
    s = clamp(s - f / max(df, 1e-6), -1.0, 1.0);
  }
  return s;
}
const float kRaisedCosineStd = 0.36151;  // sqrt(1/3 - 2/pi^2)

// What light i adds at x per unit of its luminance: cosine, emission lobe, clamped 1 / d^2.
float geometricFactor(ShadedLight light, vec3 x, vec3 n) {
  float a = luminance(light.intensity);
  if (!(a > 0.0)) return 0.0;
  return luminance(lightContribution(light.position, light.intensity, light.meanNormal, light.omniFraction, x, n,
                                     clampDistance)) /
         a;
}

// The input light a ray towards grid light g aims at. The m drawn lights follow the share of g's
// importance, w_i a_i / W. What g adds at x is sum_i w_i f_i(x), f_i = a_i G_i(x) with G_i the
// geometric factor (cosine, lobe, 1/d^2) of light i at x; so resampling the m drawn lights by
// G_i(x) (weight target / source = w_i a_i G_i / (w_i a_i)) picks light i in proportion to what it
// adds here as m grows (resampled importance sampling, Talbot et al. 2005), instead of in proportion
// to its brightness wherever it is. Without resampling: race `race` as drawn.
// drawnFactor: the estimate of sum_i (w_i a_i / W) G_i(x), g's lights' geometric factor at x (the mean
// of the m drawn lights' G, resampled; the drawn light's own G, not resampled). Unbiased either way.
uint pickTarget(uint gridLight, uint race, vec3 x, vec3 n, inout Rng rng, out float drawnFactor) {
  uint drawn = clusterTargets[gridLight * races + race];
  if (resampleTargets == 0) {
    drawnFactor = drawn != kNoLight ? geometricFactor(decodeInputLight(inputLights[drawn]), x, n) : 0.0;
    return drawn;
  }
  float total = 0.0, count = 0.0;
  uint picked = drawn;  // if no drawn light reaches x, fall back to the plain draw
  for (uint r = 0u; r < races; ++r) {
    uint candidate = clusterTargets[gridLight * races + r];
    if (candidate == kNoLight) continue;
    count += 1.0;
    float g = geometricFactor(decodeInputLight(inputLights[candidate]), x, n);
    if (!(g > 0.0)) continue;
    total += g;
    if (nextFloat(rng) * total < g) picked = candidate;
  }
  drawnFactor = count > 0.0 ? total / count : 0.0;
  return picked;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.resolution.xy)))) return;
  Surface s = loadSurface(pixel);
  uvec2 p = uvec2(pixel);
  uvec2 tiled = (p % tilesPerAxis) * tileSize + p / tilesPerAxis;
  uint pixelIndex = tiled.y * (tilesPerAxis * tileSize.x) + tiled.x;
  float visible = 0.0, weights = 0.0, rays = 0.0;
  if (s.valid) {
    vec3 origin = offsetRayOrigin(s.position, s.normal);
    Rng rng = makeRng(pixelIndex, frameSeed ^ 0x5bd1e995u);
    // Slot j reads race (first + j) mod m: a grid light picked twice at one pixel gets two independent
    // input lights (while k <= m), and neighbouring pixels mostly read different races.
    uint firstRace = races > 0u ? pcgHash(pixelIndex ^ frameSeed) % races : 0u;
    for (uint j = 0u; j < samples; ++j) {
      uint id = shadowSlots[pixelIndex * samples + j];
      if (id == kNoLight) continue;
      ShadedLight light;
      vec3 target;
      float weight = 1.0;
      if ((id & kSlotS0) != 0u) {
        light = decodeInputLight(inputLights[id & ~kSlotS0]);
        target = light.position;
      } else {
        light = decodeGridLight(gridLights[id]);
        float drawnFactor = 0.0;
        uint targetLight =
            races > 0u ? pickTarget(id, (firstRace + j) % races, s.position, s.normal, rng, drawnFactor) : kNoLight;
        if (targetLight != kNoLight) {
          target = inputLights[targetLight].position;
          // The selection drew g in proportion to its centre's contribution c_g = blend a_g G_centre(x);
          // what g's input lights add is blend a_g sum_i share_i G_i(x), estimated by drawnFactor.
          // Weighing the sample by their quotient makes the k samples' weighted mean converge to the
          // exact ratio sum_i a_i G_i V_i / sum_i a_i G_i instead of one weighted by the centres.
          if (weighTargets != 0) {
            float centre = geometricFactor(light, s.position, s.normal);
            weight = centre > 0.0 ? drawnFactor / centre : 0.0;
          }
        } else {
          vec3 sigma = sqrt(max(gridLights[id].variance, vec3(0.0)));
          vec3 jitter = vec3(raisedCosine(nextFloat(rng)), raisedCosine(nextFloat(rng)), raisedCosine(nextFloat(rng)));
          target = light.position + (spread / kRaisedCosineStd) * sigma * jitter;
        }
      }
      vec3 lightPosition = light.position;
      if (uniformSelection != 0) {
        // Uniform selection: weight each visibility by the light's contribution here (times the
        // correction above: the contribution of its input lights).
        float R = levelRadius(alpha, topCellSize, light.level, levels);
        uint role = bruteForce != 0 ? kRoleOnly : levelRole(light.level, firstLevel, levels);
        vec3 e = blendWeight(role, distance(lightPosition, s.position), R) *
                 lightContribution(lightPosition, light.intensity, light.meanNormal, light.omniFraction, s.position,
                                   s.normal, clampDistance);
        weight *= luminance(e);
      }
      weights += weight;
      // The sample adds nothing here (no drawn light reaches x): a ray would decide nothing.
      if (weight == 0.0) continue;
      vec3 toLight = target - origin;
      float d = length(toLight);
      // Stop short of the light by a relative margin: VPLs sit on surfaces, and so may a cluster's centre.
      bool blocked = d > 0.0 && traceAnyHit(origin, toLight / d, 0.0, d * (1.0 - 1e-3));
      visible += weight * (blocked ? 0.0 : 1.0);
      rays += 1.0;
    }
  }
  // No selected light (nothing lights this pixel through the LGH): visibility 1 multiplies zero anyway.
  float ratio = weights > 0.0 ? visible / weights : 1.0;
  // b: the estimate's own weight, the samples' mean weight (1 unless weighTargets), by which the filter
  // and the accumulation weigh this pixel's ratio: a ratio of sums over pixels and frames converges
  // where a mean of per-pixel ratios would keep each one's bias.
  float meanWeight = weighTargets != 0 && uniformSelection == 0 && samples > 0u ? weights / float(samples) : 1.0;
  imageStore(ratioOut, pixel, vec4(ratio, rays, meanWeight, 1.0));
}
