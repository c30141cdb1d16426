// Streaming shadow-sample selection in the light pass (Lin & Yuksel 2019, Appendix A; docs/design.md §5).
// Each pixel keeps a running importance total F and k slots. A fragment of importance f adds f to F
// and then takes each slot with probability f / F (the paper decides them independently; here they are
// stratified, below). In any order this leaves light i in a slot with probability f_i / sum f (a
// weighted reservoir of size 1 per slot).
//
// Concurrent fragments of one pixel: F is advanced with one atomic add, which puts the fragments in
// a single order and hands each its own prefix total; the slot write is an atomic exchange. The
// result is exact when the exchanges land in the order of the adds, which holds whenever a pixel's
// fragments are shaded one after another (llvmpipe shades each tile on one thread, in primitive
// order; GPUs shade overlapping fragments of one pixel in order for blending, but their SSBO writes
// are not ordered, so two fragments shaded together can swap: a bias bounded by how often two
// fragments of one pixel are in flight at once). Without float atomics (LGH_SELECTION_NO_ATOMICS)
// it is the paper's plain read-modify-write, exact under the same in-order condition.
#ifndef LGH_SHADOW_SELECTION_GLSL
#define LGH_SHADOW_SELECTION_GLSL
#include "shared/light_pass_types.h"
#include "shared/sampling.glsl"

layout(std430, binding = LGH_BINDING_PASS1) coherent buffer ShadowTotals { float shadowTotals[]; };
layout(std430, binding = LGH_BINDING_PASS2) coherent buffer ShadowSlots { uint shadowSlots[]; };
// What grid lights that reach the pixel but cannot be selected there add (luminance, on the scale of F):
// completes the samples' estimate of the unshadowed sum (shadow_rays.comp, T).
layout(std430, binding = LGH_BINDING_PASS3) coherent buffer ShadowUnselectable { float shadowUnselectable[]; };

void addUnselectable(uint pixelIndex, float added) {
#ifdef LGH_SELECTION_NO_ATOMICS
  shadowUnselectable[pixelIndex] += added;
#else
  atomicAdd(shadowUnselectable[pixelIndex], added);
#endif
}

void selectShadowSample(uint pixelIndex, uint lightId, float importance, uint k, uint frameSeed) {
  if (importance <= 0.0 || k == 0u) return;
#ifdef LGH_SELECTION_NO_ATOMICS
  float total = shadowTotals[pixelIndex] + importance;
  shadowTotals[pixelIndex] = total;
#else
  float total = atomicAdd(shadowTotals[pixelIndex], importance) + importance;
#endif
  // Stratified over the slots: the fragment takes c = floor(k p + u) of them, p = importance / total, a
  // uniformly random c of the k (selection sampling, Knuth's Algorithm S: slot j is taken with
  // probability (still to take) / (slots left)). Each slot is still taken with probability p, by
  // uniforms independent of other fragments', so each slot alone is the reservoir above; but the k
  // slots now hold a light about k p_i times rather than binomially often (and small lights, k p < 1,
  // at most once: sampling without replacement), so the k samples' mean varies less, the more so the
  // larger k. Most fragments take no slot and draw one uniform. Hashed per (pixel, light, frame).
  Rng rng = makeRng(lightId * 2654435761u ^ pixelIndex, frameSeed);
  uint taken = min(uint(float(k) * (importance / total) + nextFloat(rng)), k);
  for (uint j = 0u; j < k && taken > 0u; ++j) {  // once taken = k - j every slot left is taken
    if (nextFloat(rng) * float(k - j) < float(taken)) {
      --taken;
#ifdef LGH_SELECTION_NO_ATOMICS
      shadowSlots[pixelIndex * k + j] = lightId;
#else
      atomicExchange(shadowSlots[pixelIndex * k + j], lightId);
#endif
    }
  }
}
#endif
