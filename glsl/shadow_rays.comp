#version 450 core
#extension GL_ARB_shader_ballot : enable
#extension GL_ARB_gpu_shader_int64 : enable
// One shadow ray per selected light per pixel (docs/design.md §5), from the pixel's surface to the light:
// this shader weighs each slot and queues its ray, shadow_trace.comp traces the queue (any-hit through
// the scene BVH) and shadow_ratio.comp sums each pixel's visible weights. A selected grid light is
// reached through one of its input lights, drawn by its share of the grid light's importance
// (shadow_targets.comp), or, as in the paper, through its centre jittered by the cluster's spread (when
// no targets were drawn).
// The light pass drew each slot's light l with probability c'_l / F' (c'_l: its selection importance,
// F': the pixel's total, shadowTotals). Sample j is weighed by w_j = t_l / c'_l, t_l what l adds here
// unshadowed: for a grid light with drawn targets (weighTargets), what its input lights add, estimated
// by the drawn lights' mean blended geometric factor; otherwise its own blended contribution. Each drawn
// light is blended by its own distance to x (blendTargets): the levels' B_l sum to 1 at every distance,
// so over all levels input light i counts a_i G_i(x) exactly; blended by its grid light's centre's
// distance instead, a light near x can count at a fine level and again at a coarse one whose centre is
// far, or at neither. Then, up to the lights of grid lights the selection cannot reach at x,
//   F' mean(w V) estimates the shadowed irradiance's luminance sum_i a_i G_i V_i, and
//   F' mean(w)   the unshadowed one, sum_i a_i G_i, which the LGH's irradiance (luminance C) approximates;
// the light pass adds what those lights add, U (one drawn light each, light_volume.frag), so that
//   T = F' mean(w) + U estimates the whole unshadowed sum.
// Writes each slot's weight w (0 for an empty slot; shadow_trace.comp zeroes it where the ray is blocked)
// and queues the rays; its image holds sum w (red, which shadow_ratio.comp makes the raw visibility
// ratio r = sum w V / sum w), the variance of T (green) and the ratio's weight T (blue): the samples' estimate of what the input lights add here, on the scale of
// the light pass's irradiance, by which the filter and the accumulation weigh the ratio; and, as a second
// image, the luminance C of the light pass's irradiance the samples were drawn against (with n x n
// interleaving the pixel's own tile's, n^2-scaled and unresolved: its lights are the ones T estimates).
// Sums of T over sums of C estimate D, what the input lights add over what the LGH's lights add, by
// which the irradiance is corrected as far as T's variance allows (docs/design.md §5, "Weighing the
// samples" and "Correcting the irradiance"). Only sums are divided: one tile's C can be all but 0 where
// T is not. Comparing a tile's T with the resolved irradiance instead would make D vary from tile to
// tile by what the tile's lights add, an error that more samples do not shrink and T's variance does
// not show (issue 28: with it, k = 16 was worse than k = 4 at 4 x 4).
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.h"
#include "shared/bvh_types.h"
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
#include "shared/shadow_ray.glsl"
#include "shared/shadow_ray_types.h"

// The input lights S0 as integer texels, a GpuLight two (position and normal, intensity and flags): its
// floats' bits cast back exactly, so that a light is two fetches, not two of each view.
layout(binding = LGH_TEXTURE_SHADOW_INPUT_LIGHTS) uniform usamplerBuffer inputLightTexels;
GpuLight inputLight(uint i) {
  int texel = 2 * int(i);
  uvec4 a = texelFetch(inputLightTexels, texel), b = texelFetch(inputLightTexels, texel + 1);
  return GpuLight(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w);
}
layout(std430, binding = LGH_BINDING_PASS1) readonly buffer ShadowTotals { float shadowTotals[]; };  // F'
layout(binding = LGH_TEXTURE_SHADOW_IRRADIANCE) uniform sampler2D lightPassIrradiance;  // the slots' layout
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer ShadowSlots { uint shadowSlots[]; };
layout(std430, binding = LGH_BINDING_PASS3) readonly buffer GridLights { GpuGridLight gridLights[]; };
layout(std430, binding = LGH_BINDING_PASS4) readonly buffer Targets { uint clusterTargets[]; };
// What the grid lights that reach the pixel but cannot be selected there add (light_volume.frag,
// countUnselectable; 0 unless ShadowSettings::countsUnselectable).
layout(std430, binding = LGH_BINDING_PASS5) readonly buffer ShadowUnselectable { float shadowUnselectable[]; };
// Each slot's weight w, at (y W + x) k + j, and the queue: its counts, then a QueuedShadowRay a texel.
layout(std430, binding = LGH_BINDING_PASS7) writeonly buffer SlotWeights { float slotWeights[]; };
layout(std430, binding = LGH_BINDING_PASS0) buffer QueueCounts { ShadowRayQueueCounts queued; };
layout(rgba32ui, binding = LGH_IMAGE_SHADOW_QUEUE) uniform writeonly uimageBuffer queuedRays;
layout(rgba32f,
       binding = LGH_IMAGE_SHADOW_RATIO) uniform writeonly image2D ratioOut;  // r: sum w, g: T's variance, b: T
layout(r32f, binding = LGH_IMAGE_SHADOW_SAMPLED_IRRADIANCE) uniform writeonly image2D sampledIrradianceOut;  // C

layout(std140, binding = LGH_UBO_PASS) uniform ShadowRays { ShadowRayUniforms rays; };
#ifdef LGH_SHADOW_RAYS_RECORD
// The rays queued, recorded for lgh-bench rays: slot j of pixel (x, y) at (j H + y) W + x (image order, slot
// by slot: neighbouring rays leave neighbouring pixels, as in the queue); tMax 0 where no ray was queued.
layout(std430, binding = LGH_BINDING_PASS6) writeonly buffer RecordedRays { GpuRay recordedRays[]; };
#endif

// The light pass's selection (rays.selectFlags, as light_volume.frag read them).
bool uniformSelection() { return (rays.selectFlags & kSelectUniform) != 0u; }
// False when the finest level is skipped: F' / C then compares unlike sums.
bool everyLevelSelected() { return (rays.selectFlags & kSelectSkipFinest) == 0u; }
// Blend each drawn light by its own distance (else by its grid light's centre's).
bool blendTargets() { return (rays.selectFlags & kSelectBlendTargets) != 0u; }

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

// What input light `light`, drawn for a grid light of role `role` and radius R, adds at x per unit of
// its grid light's luminance share: its geometric factor, blended by its own distance (blendTargets).
float drawnFactorOf(uint light, vec3 x, vec3 n, uint role, float R) {
  ShadedLight l = decodeInputLight(inputLight(light));
  float g = geometricFactor(l, x, n, rays.clampDistance);
  return blendTargets() && g > 0.0 ? g * blendWeight(role, distance(l.position, x), R) : g;
}

// The input light a ray towards grid light g aims at. The m drawn lights follow the share of g's
// importance, w_i a_i / W. What g adds at x is sum_i w_i f_i(x), f_i = a_i G_i(x) with G_i the
// geometric factor (cosine, lobe, 1/d^2) of light i at x; so resampling the m drawn lights by
// G_i(x) (weight target / source = w_i a_i G_i / (w_i a_i)) picks light i in proportion to what it
// adds here as m grows (resampled importance sampling, Talbot et al. 2005), instead of in proportion
// to its brightness wherever it is (with blendTargets, by B_l(|x - p_i|) G_i(x), the blended factor).
// Without resampling: race `race` as drawn.
// drawnFactor: the estimate of sum_i (w_i a_i / W) B_l(|x - p_i|) G_i(x), g's lights' blended geometric
// factor at x (the mean of the m drawn lights', resampled; the drawn light's own, not resampled; without
// blendTargets, G_i alone). Unbiased either way.
uint pickTarget(uint gridLight, uint race, vec3 x, vec3 n, uint role, float R, inout Rng rng, out float drawnFactor) {
  uint drawn = clusterTargets[gridLight * rays.races + race];
  if (rays.resampleTargets == 0u) {
    drawnFactor = drawn != kNoLight ? drawnFactorOf(drawn, x, n, role, R) : 0.0;
    return drawn;
  }
  float total = 0.0, count = 0.0;
  uint picked = drawn;  // if no drawn light reaches x, fall back to the plain draw
  for (uint r = 0u; r < rays.races; ++r) {
    uint candidate = clusterTargets[gridLight * rays.races + r];
    if (candidate == kNoLight) continue;
    count += 1.0;
    float g = drawnFactorOf(candidate, x, n, role, R);
    if (!(g > 0.0)) continue;
    total += g;
    if (nextFloat(rng) * total < g) picked = candidate;
  }
  drawnFactor = count > 0.0 ? total / count : 0.0;
  return picked;
}

// The weight w = t_l / c'_l of the sample in slot j, selected light `id` (0: it adds nothing here), and
// the point its ray aims at.
float weighSlot(uint id, uint j, Surface s, uint firstRace, inout Rng rng, out vec3 target) {
  bool gridLight = (id & kSlotS0) == 0u;
  ShadedLight light = gridLight ? decodeGridLight(gridLights[id]) : decodeInputLight(inputLight(id & ~kSlotS0));
  float R = levelRadius(rays.alpha, rays.topCellSize, light.level, rays.levels);
  uint role = rays.bruteForce != 0u ? kRoleOnly : levelRole(light.level, rays.firstLevel, rays.levels);
  target = light.position;
  float drawnFactor = -1.0;  // < 0: no drawn targets (an S0 light, or a jittered centre)
  if (gridLight) {
    uint targetLight = rays.races > 0u ? pickTarget(id, (firstRace + j) % rays.races, s.position, s.normal, role, R,
                                                    rng, drawnFactor)
                                       : kNoLight;
    if (targetLight != kNoLight) {
      target = inputLight(targetLight).position;
    } else {
      drawnFactor = -1.0;
      vec3 sigma = sqrt(max(gridLights[id].variance, vec3(0.0)));
      vec3 jitter = vec3(raisedCosine(nextFloat(rng)), raisedCosine(nextFloat(rng)), raisedCosine(nextFloat(rng)));
      target = light.position + (rays.spread / kRaisedCosineStd) * sigma * jitter;
    }
  }
  // The light's selection importance c'_l, as the light pass computed it (light_volume.frag).
  float d = distance(light.position, s.position);
  float blend = blendWeight(role, d, R);
  LightSelection lit = lightSelection(light, s.position, s.normal, d, blend, gridLight, rays.clampDistance,
                                      rays.defensive, uniformSelection());
  // What it adds here: the selection drew grid light g in proportion to c'_g, but what g's input
  // lights add is a_g sum_i share_i B_l(|x - p_i|) G_i(x) (blend a_g sum_i share_i G_i(x) without
  // blendTargets), estimated by drawnFactor. Weighing the sample by their quotient makes the weighted
  // mean of the visibilities converge to the exact ratio sum_i a_i G_i V_i / sum_i a_i G_i instead of
  // one weighted by the centres.
  float added = rays.weighTargets != 0u && drawnFactor >= 0.0
                    ? (blendTargets() ? 1.0 : blend) * luminance(light.intensity) * drawnFactor
                    : luminance(lit.irradiance);
  return lit.importance > 0.0 ? added / lit.importance : 0.0;
}

// A place in the queue for this invocation's ray, and the trace's groups counted as the queue grows past
// each multiple of kShadowTraceGroupSize. Where the driver has ballots, one atomic serves every
// invocation of the subgroup that queues a ray now, in lane order (llvmpipe does an atomic one lane at a
// time; a GPU serialises atomics on one address); else one atomic a ray.
uint queueIndex() {
#if defined(GL_ARB_shader_ballot) && defined(GL_ARB_gpu_shader_int64)
  uint64_t queuing = ballotARB(true);
  uvec2 all = unpackUint2x32(queuing), below = unpackUint2x32(queuing & gl_SubGroupLtMaskARB);
  uint count = bitCount(all.x) + bitCount(all.y), rank = bitCount(below.x) + bitCount(below.y);
  uint first = 0u;
  if (rank == 0u) {
    first = atomicAdd(queued.rays, count);
    uint groups = (first + count + kShadowTraceGroupSize - 1u) / kShadowTraceGroupSize -
                  (first + kShadowTraceGroupSize - 1u) / kShadowTraceGroupSize;
    if (groups > 0u) atomicAdd(queued.groupsX, groups);
  }
  return readFirstInvocationARB(first) + rank;
#else
  uint index = atomicAdd(queued.rays, 1u);
  if (index % kShadowTraceGroupSize == 0u) atomicAdd(queued.groupsX, 1u);
  return index;
#endif
}

// Queues slot `slot`'s ray from `origin` to `target` (shadowRay, which shadow_trace.comp makes again); a
// ray of length 0 is not blocked and not queued.
void queueRay(vec3 origin, vec3 target, uint slot) {
  GpuRay ray = shadowRay(origin, target);
  if (!(ray.tMax > 0.0)) return;
  uint index = queueIndex();
  imageStore(queuedRays, 1 + int(index), uvec4(floatBitsToUint(target), slot));
#ifdef LGH_SHADOW_RAYS_RECORD
  uvec2 p = shadowSlotPixel(slot, rays.samples);
  recordedRays[((slot % rays.samples) * uint(frame.resolution.y) + p.y) * uint(frame.resolution.x) + p.x] = ray;
#endif
}

void main() {
  // The rows of this batch (ShadowRayPass queues the rays of as many rows as its queue holds, in turn).
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, rays.firstRow);
  if (pixel.x >= int(frame.resolution.x) || pixel.y >= int(rays.endRow)) return;
  Surface s = loadSurface(pixel);
  uvec2 p = uvec2(pixel);
  uvec2 tiled = (p % rays.tilesPerAxis) * uvec2(rays.tileWidth, rays.tileHeight) + p / rays.tilesPerAxis;
  uint pixelIndex = tiled.y * (rays.tilesPerAxis * rays.tileWidth) + tiled.x;  // in the light pass's layout
  uint firstSlot = shadowFirstSlot(p, rays.samples);
  float weights = 0.0, squares = 0.0, estimate = 0.0, variance = 0.0;
  if (s.valid) {
    vec3 origin = offsetRayOrigin(s.position, s.normal);
    Rng rng = makeRng(pixelIndex, rays.frameSeed ^ 0x5bd1e995u);
    // Slot j reads race (first + j) mod m: a grid light picked twice at one pixel gets two independent
    // input lights (while k <= m), and neighbouring pixels mostly read different races.
    uint firstRace = rays.races > 0u ? pcgHash(pixelIndex ^ rays.frameSeed) % rays.races : 0u;
    for (uint j = 0u; j < rays.samples; ++j) {
      uint id = shadowSlots[pixelIndex * rays.samples + j];
      vec3 target;
      float weight = id != kNoLight ? weighSlot(id, j, s, firstRace, rng, target) : 0.0;
      weights += weight;
      squares += weight * weight;
      slotWeights[firstSlot + j] = weight;
      // A sample that adds nothing here (no drawn light reaches x) needs no ray: it decides nothing.
      if (weight != 0.0) queueRay(origin, target, firstSlot + j);
    }
  }
  // b: the estimate's own weight T = F' mean(w) = C D (C: the light pass's irradiance here, in its layout), by which the filter
  // and the accumulation weigh this pixel's ratio (a ratio of sums over pixels and frames converges where
  // a mean of per-pixel ratios would keep each one's bias), and whose sums over sums of C may correct the
  // LGH's irradiance. With the finest level skipped the samples cover only part of C: D is then the plain
  // mean weight. Uniform selection, the paper's comparison of ratio estimators, keeps D = 1: its estimate
  // of the sum, (number of lights) x mean(w), is too noisy to weigh or correct anything by.
  float lgh = luminance(texelFetch(lightPassIrradiance, ivec2(tiled), 0).rgb);
  if (uniformSelection()) {
    estimate = lgh;
  } else if (s.valid && rays.samples > 0u) {
    float k = float(rays.samples), meanWeight = weights / k;
    float scale = everyLevelSelected() ? shadowTotals[pixelIndex] : lgh;  // T = scale x mean(w) (+ unselectable)
    estimate = scale * meanWeight + shadowUnselectable[pixelIndex];
    // T's variance, by which the filter trusts the correction: one sample's variance over k, that
    // variance the k samples' own (unbiased: their squared deviations over k - 1) pooled with a prior
    // worth one sample, (sampleSpread C)^2, so that one sample, or k alike by chance, is not taken for a
    // certain D: ((sampleSpread C)^2 + sum (T_j - T)^2) / k, over k.
    float deviations = scale * scale * max(squares - k * meanWeight * meanWeight, 0.0);  // sum (T_j - T)^2
    variance = (rays.sampleSpread * rays.sampleSpread * lgh * lgh + deviations) / (k * k);
  }
  imageStore(ratioOut, pixel, vec4(weights, variance, estimate, 1.0));
  imageStore(sampledIrradianceOut, pixel, vec4(s.valid ? lgh : 0.0));
}
