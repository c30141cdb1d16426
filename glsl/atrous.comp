#version 450 core
// Edge-avoiding a-trous wavelet filter (Dammertz et al. 2010) of the shadow ratio, as a ratio
// estimator (Heitz et al. 2018): the shadowed (S = U D x raw ratio) and unshadowed (U D) luminances are
// filtered with the same weights and divided at the end, so the ratio is averaged in proportion to
// the light each neighbour receives (U D: the raw ratio's own weight, what its samples estimate the
// input lights add, blue; shadow_rays.comp). The same taps filter the irradiance the samples were drawn
// against (U: the sampled irradiance, with interleaving each pixel's own tile's, so that both sums cover
// the same lights), so that U D / U is the filtered mean weight, a ratio of sums (no pixel's U D is
// divided by its own U): an estimate of what the input lights add over what the LGH's grid lights add
// (docs/design.md §5, "Correcting the irradiance"). With correctIrradiance the output is the ratio times it, shrunk toward 1 by how
// uncertain it is: 1 + f^2 / (f^2 + var D) (D - 1), the Bayes estimate of D under a prior of spread f
// (the LGH irradiance's expected relative error) around the LGH's irradiance (D = 1). So a noisy D keeps
// the LGH's irradiance, and as the samples, taps and frames make D certain the image converges to the
// exact shadowed irradiance instead of the LGH's times the exact ratio. D's variance comes with the raw
// ratio (green: var(U D), its samples' spread pooled with a prior, shadow_rays.comp; over N frames the
// sum of theirs / N^2, accumulate.comp). The first averaging (the interleaving's resolve, else the first
// pass) averages independent pixels, so it filters that variance with the squared tap weights (as Schied
// et al. 2017 do for every pass); later passes average
// overlapping neighbourhoods of those averages, whose noise is correlated, and their blur biases D where
// it varies, so they claim no further certainty (measured: trusting their squared weights too made the
// corrected image worse than the uncorrected one at alpha 0.5). The ratio's edge-stopping stays on
// S / (U D), which is in [0, 1], so a pixel's heavy weight is averaged, not kept.
// With temporal accumulation the ratio holds N frames (alpha of the raw ratio): its noise falls as
// 1/sqrt(N), and the ratio sigma shrinks as N^-sigmaFade and the pixel skips the floor(sigmaFade
// log2 N) widest passes (at fade 1/2: one per 4x the frames, as the noise halves), so that the filter's
// blur across shadow edges and contact shadows does not become the accumulated estimate's error floor:
// the filter vanishes as N grows.
// With n x n interleaving a pixel's samples saw only its tile's lights: its ratio is its tile's visibility
// and its mean weight its tile's D, each off the pixel's own by what its tile's lights happen to be, an
// error that more samples do not shrink. So, as the irradiance is resolved (interleave_resolve.comp), the
// sums are first resolved over the same window (shared/interleave_window.glsl, which shrinks as the
// accumulated frames cover more tiles): S, U D, U summed over all tiles' pixels around, var with squared
// weights; the a-trous passes then claim no further certainty.
//   stage 0: (raw ratio, sampled irradiance) -> (S, U D, U, var(U D))
//   resolve: (interleaving) the same, summed over the interleaving window
//   stage 1: one 5x5 B3-spline pass with holes of `stepSize` over (S, U D, U); var with squared weights
//            in the first pass (step 1) unless the resolve ran, kept in the others
//   stage 2: (S, U D, U, var) -> visibility factor (r): S / (U D), times the shrunk correction with
//            correctIrradiance; the ratio S / (U D) (g) and the mean weight U D / U (b); the raw ratio
//            where U D is 0, mean weight 1 where U is 0
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/atrous_taps.glsl"
#include "shared/interleave_window.glsl"
#include "shared/shadow_filter_types.h"

layout(binding = LGH_TEXTURE_FILTER_SIGNAL)
    uniform sampler2D signalIn;  // stage 0: raw ratio (r), var(U D) (g), U D (b), frames (a); 1, 2: (S, U D, U, var)
layout(binding = LGH_TEXTURE_FILTER_SECOND) uniform sampler2D
    second;  // the sampled irradiance's luminance U (r, stage 0), the raw ratio (stages 1, 2)
layout(rgba32f, binding = LGH_IMAGE_FILTER_OUT) uniform writeonly image2D signalOut;
layout(std140, binding = LGH_UBO_PASS) uniform ShadowFilter { ShadowFilterUniforms atrous; };

// A weight U D below this has no ratio: llvmpipe flushes denormals in arithmetic but not in comparisons, so
// a denormal U D > 0 could still divide 0 by 0.
const float kNoWeight = 1e-30;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.resolution.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  if (atrous.stage == kFilterPrepare) {
    vec4 raw = texelFetch(signalIn, pixel, 0);
    float u = max(texelFetch(second, pixel, 0).r, 0.0), weighted = max(raw.b, 0.0);  // U, U D
    imageStore(signalOut, pixel, vec4(weighted * raw.r, weighted, u, max(raw.g, 0.0)));
    return;
  }
  vec4 centre = texelFetch(signalIn, pixel, 0);
  vec4 raw = texelFetch(second, pixel, 0);  // the raw ratio: r, var(U D) g, U D b, frames a
  if (atrous.stage == kFilterFinish) {
    // S <= U D tap by tap (a ratio is at most 1), so S / (U D) stays in [0, 1] however small U D is; only
    // U D = 0 (no light, or every sample weighed 0) has no quotient.
    float ratio = clamp(centre.g > kNoWeight ? centre.r / centre.g : raw.r, 0.0, 1.0);
    float meanWeight = centre.b > 0.0 ? centre.g / centre.b : 1.0;  // U = 0: nothing to correct
    // The correction trusts the mean weight as far as it is more certain than the LGH's irradiance:
    // f^2 / (f^2 + var D), var D = var(U D) / U^2 (U is exact: the irradiance the samples were drawn against).
    float varianceOfD = centre.b > 0.0 ? centre.a / (centre.b * centre.b) : 0.0;
    float prior = atrous.lghError * atrous.lghError;
    // Where the LGH's irradiance is all but 0 and the samples' T is not, U underflows against U D: D and its
    // variance have no finite value (inf, or 0 / 0), and nothing is trusted (the irradiance corrected is ~0).
    float trust = prior > 0.0 && varianceOfD < 3.0e38 ? prior / (prior + varianceOfD) : 0.0;
    float correction = trust > 0.0 ? 1.0 + trust * (meanWeight - 1.0) : 1.0;
    float visibility = atrous.correctIrradiance != 0u ? ratio * correction : ratio;
    imageStore(signalOut, pixel, vec4(visibility, ratio, meanWeight, 1.0));
    return;
  }
  Surface s = loadSurface(pixel);
  if (!s.valid) {
    imageStore(signalOut, pixel, centre);
    return;
  }
  float frames = max(raw.a, 1.0);  // accumulated (1 for a single frame)
  ivec2 resolveWindow = interleaveHalfWidths(atrous.tilesPerAxis, frames);
  if (atrous.stage == kFilterResolve) {
    // The window's taps, kept for the spread below: at most (n + 1)^2 = 81 (n <= 8, gpu::kMaxInterleave).
    vec4 taps[81];
    float tapWeights[81];
    int tapCount = 0;
    vec3 sum = vec3(0.0);
    float weightSum = 0.0, varianceSum = 0.0;
    for (int dy = -resolveWindow.y; dy <= resolveWindow.y; ++dy) {
      for (int dx = -resolveWindow.x; dx <= resolveWindow.x; ++dx) {
        float w = interleaveTapWeight(s, pixel, ivec2(dx, dy), atrous.tilesPerAxis, resolveWindow, atrous.normalPower,
                                      atrous.planeSigma);
        if (!(w > 0.0)) continue;
        vec4 v = texelFetch(signalIn, pixel + ivec2(dx, dy), 0);
        sum += w * v.rgb;
        varianceSum += w * w * v.a;
        weightSum += w;
        taps[tapCount] = v;
        tapWeights[tapCount++] = w;
      }
    }
    // The pixel's own tap has weight 1, so weightSum > 0. The window's mean weight D = sum U D / sum U is a
    // ratio estimator over pixels of different tiles: besides its samples' variance (the taps' var(U D)),
    // it varies by what each tile's lights add here, which no number of samples shrinks (a tile holding a
    // light close to its pixel adds n^2 times it there). Its variance, on the scale of U D, is estimated
    // from the window's own spread as a ratio estimator's (Cochran 1977, 6.3):
    // sum w^2 (U D_q - D U_q)^2 / (sum w)^2. That spread holds the samples' noise too, but from a few taps
    // it can come out small by chance: the larger of it and the samples' own variance is taken, so that
    // the correction is trusted as far as the tiles agree and their samples allow. (Measured: scaling the
    // spread by m / (m - 1), m the taps' effective count, and not trusting D at all below m = 2 made every
    // interleaved k = 16 frame worse, docs/measurements.md.)
    float meanWeight = sum.b > 0.0 ? sum.g / sum.b : 1.0;
    float spread = 0.0;
    for (int i = 0; i < tapCount; ++i) {
      float residual = taps[i].g - meanWeight * taps[i].b;
      spread += tapWeights[i] * tapWeights[i] * residual * residual;
    }
    imageStore(signalOut, pixel, vec4(sum / weightSum, max(varianceSum, spread) / (weightSum * weightSum)));
    return;
  }
  int kept = atrous.passes - int(floor(atrous.sigmaFade * log2(frames)));
  if (atrous.stepSize >= (1 << clamp(kept, 0, 30))) {  // one of the widest passes, skipped at N frames
    imageStore(signalOut, pixel, centre);
    return;
  }
  float footprint = atrousFootprint(s, atrous.stepSize);
  float centreRatio = centre.g > kNoWeight ? centre.r / centre.g : raw.r;
  float sigma = atrous.ratioSigma * pow(frames, -atrous.sigmaFade);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0, varianceSum = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q;
      vec4 qPosition;
      if (!atrousTap(pixel, ivec2(dx, dy), atrous.stepSize, q, qPosition)) continue;
      vec4 v = texelFetch(signalIn, q, 0);
      float qRatio = v.g > kNoWeight ? v.r / v.g : centreRatio;  // a tap without a ratio stops nothing
      float dr = atrous.stepSize > 1 ? (qRatio - centreRatio) / sigma : 0.0;
      float w = atrousTapWeight(s, ivec2(dx, dy), q, qPosition, footprint, atrous.normalPower, atrous.planeSigma,
                                dr * dr);
      sum += w * v.rgb;
      varianceSum += w * w * v.a;
      weightSum += w;
    }
  }
  // The centre tap has weight (3/8)^2 > 0, so weightSum > 0. Only the first averaging of independent
  // pixels (this pass's, or the interleaving's resolve) claims the certainty of its squared weights.
  bool firstAveraging = atrous.stepSize == 1 && resolveWindow == ivec2(0);
  float variance = firstAveraging ? varianceSum / (weightSum * weightSum) : centre.a;
  imageStore(signalOut, pixel, vec4(sum / weightSum, variance));
}
