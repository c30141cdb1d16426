#version 450 core
// The stochastic lightcuts' denoiser, variance-guided as their paper's (Lin & Yuksel 2020 filter with
// SVGF: Schied et al. 2017; docs/design.md §12). The lightcuts' estimate is unbiased noise around the
// shadowed irradiance, with no noise-free unshadowed part to filter a ratio against (atrous.comp), so the
// edge-avoiding a-trous passes stop on the luminance difference scaled by its own noise:
//   w_l = exp(-|l_p - l_q| / (sigma_l sqrt(g3x3(var)_p))),
// wide open where the estimate is noisy and closing as it converges. (A fixed relative-luminance stop made
// a bright sample and its neighbours reject each other, so the outliers the filter should spread survived:
// filtered / raw 0.40 at 4 samples per pixel, docs/measurements.md.) The variance is filtered with the
// squared weights, so each pass stops on the noise of what it filters.
//   stage 0: the m x m interleaving resolved (each pixel of a group took 1/m^2 of the cut's nodes, rotated
//            every frame: the window of shared/interleave_window.glsl, as the LGH's tiles are put back), and
//            each pixel's luminance variance: from the accumulation's temporal moments once the pixel's
//            history holds minTemporal frames, else spatially from its 7 x 7 neighbours on the same surface
//            (weighted moments, with the effective count's correction n / (n - 1)); the resolve's squared
//            weights carry it to the resolved value. Out: (resolved irradiance, variance).
//   stage 1: one 5 x 5 pass with holes of stepSize (shared/atrous_taps.glsl: the shadow filter's kernel,
//            normal and plane weights) and the luminance stop; over N accumulated frames the
//            floor(sigmaFade log2 N) widest passes are skipped, as the shadow filter does.
// With 0 passes the output is stage 0's: the resolved irradiance with its variance in alpha.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/color.glsl"
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/atrous_taps.glsl"
#include "shared/interleave_window.glsl"
#include "shared/irradiance_filter_types.h"

layout(binding = LGH_TEXTURE_FILTER_SIGNAL) uniform sampler2D signalIn;  // stage 0: rgb irradiance; 1: (rgb, var)
layout(binding = LGH_TEXTURE_FILTER_SECOND) uniform sampler2D moments;  // accumulated: g the mean's variance, a N
layout(rgba32f, binding = LGH_IMAGE_FILTER_OUT) uniform writeonly image2D signalOut;
layout(std140, binding = LGH_UBO_PASS) uniform IrradianceFilter { IrradianceFilterUniforms filtering; };

float framesAt(ivec2 pixel) { return filtering.hasMoments != 0u ? max(texelFetch(moments, pixel, 0).a, 1.0) : 1.0; }

// The variance of one pixel's luminance, from its neighbours on the same surface: weighted moments
// mu2 - mu1^2, times n / (n - 1) for the effective count n = (sum w)^2 / sum w^2 (unbiased for independent
// pixels of one mean; 0 where the pixel has no neighbour to compare with).
float spatialVariance(Surface s, ivec2 pixel) {
  float weightSum = 0.0, squaredWeights = 0.0, first = 0.0, second = 0.0;
  for (int dy = -3; dy <= 3; ++dy) {
    for (int dx = -3; dx <= 3; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      float w = surfaceSimilarity(s, q, filtering.normalPower, filtering.planeSigma);
      if (!(w > 0.0)) continue;
      float l = luminance(texelFetch(signalIn, q, 0).rgb);
      weightSum += w;
      squaredWeights += w * w;
      first += w * l;
      second += w * l * l;
    }
  }
  float effective = weightSum * weightSum / max(squaredWeights, 1e-30);
  if (!(effective > 1.001)) return 0.0;
  float mean = first / weightSum;
  return max(second / weightSum - mean * mean, 0.0) * effective / (effective - 1.0);
}

void resolveAndEstimate(ivec2 pixel, Surface s) {
  float frames = framesAt(pixel);
  float variance = filtering.hasMoments != 0u && frames >= float(filtering.minTemporal)
                       ? max(texelFetch(moments, pixel, 0).g, 0.0)
                       : spatialVariance(s, pixel);
  ivec2 window = interleaveHalfWidths(filtering.interleave, frames);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0, squaredWeights = 0.0;
  for (int dy = -window.y; dy <= window.y; ++dy) {
    for (int dx = -window.x; dx <= window.x; ++dx) {
      float w = interleaveTapWeight(s, pixel, ivec2(dx, dy), filtering.interleave, window, filtering.normalPower,
                                    filtering.planeSigma);
      if (!(w > 0.0)) continue;
      sum += w * texelFetch(signalIn, pixel + ivec2(dx, dy), 0).rgb;
      weightSum += w;
      squaredWeights += w * w;
    }
  }
  // The pixel's own tap has weight 1. Its neighbours' variances are taken as its own.
  imageStore(signalOut, pixel, vec4(sum / weightSum, variance * squaredWeights / (weightSum * weightSum)));
}

// A 3 x 3 Gaussian of the variance around the pixel, over the taps on a surface (SVGF's g3x3: one pixel's
// variance estimate is itself noisy).
float prefilteredVariance(ivec2 pixel) {
  const float kernel[2] = float[](0.5, 0.25);
  float sum = 0.0, weightSum = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(frame.resolution.xy)))) continue;
      if (texelFetch(gPosition, q, 0).w == 0.0) continue;
      float w = kernel[abs(dx)] * kernel[abs(dy)];
      sum += w * texelFetch(signalIn, q, 0).a;
      weightSum += w;
    }
  }
  return sum / weightSum;  // the centre is on a surface
}

void filterPass(ivec2 pixel, Surface s, vec4 centre) {
  int kept = filtering.passes - int(floor(filtering.sigmaFade * log2(framesAt(pixel))));
  if (filtering.stepSize >= (1 << clamp(kept, 0, 30))) {  // one of the widest passes, skipped at N frames
    imageStore(signalOut, pixel, centre);
    return;
  }
  float footprint = atrousFootprint(s, filtering.stepSize);
  float scale = filtering.luminanceSigma * sqrt(prefilteredVariance(pixel));
  float centreLuminance = luminance(centre.rgb);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0, varianceSum = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q;
      vec4 qPosition;
      if (!atrousTap(pixel, ivec2(dx, dy), filtering.stepSize, q, qPosition)) continue;
      vec4 v = texelFetch(signalIn, q, 0);
      float difference = abs(luminance(v.rgb) - centreLuminance);
      // Where the variance is 0 (every neighbour alike) only equal taps pass; 0 / 0 is no difference.
      float stop = difference > 0.0 ? 2.0 * difference / max(scale, 1e-30) : 0.0;
      float w = atrousTapWeight(s, ivec2(dx, dy), q, qPosition, footprint, filtering.normalPower,
                                filtering.planeSigma, stop);
      sum += w * v.rgb;
      varianceSum += w * w * v.a;
      weightSum += w;
    }
  }
  // The centre tap has weight (3/8)^2 > 0.
  imageStore(signalOut, pixel, vec4(sum / weightSum, varianceSum / (weightSum * weightSum)));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.resolution.xy)))) return;
  vec4 centre = texelFetch(signalIn, pixel, 0);
  Surface s = loadSurface(pixel);
  if (!s.valid) {
    imageStore(signalOut, pixel, vec4(centre.rgb, 0.0));
    return;
  }
  if (filtering.stage == kIrradianceVariance)
    resolveAndEstimate(pixel, s);
  else
    filterPass(pixel, s, centre);
}
