#version 450 core
// Temporal accumulation of the indirect light's raw estimates (docs/design.md §6, "accumulation"):
// each pixel finds its surface in the previous frame (reprojected through the previous camera) and,
// when the surface there is the same (tangent-plane distance and normal), adds this frame's raw
// values to the history's sums:
//   irradiance sum  rgb: sum of E_f (unresolved: with n x n interleaving the tile's n^2-scaled value)
//                   a:   N, frames in the history
//   ratio sum       r: sum of T_f r_f, g: sum of T_f, b: sum of var(T_f), a: the last frame's resolved
//                   irradiance luminance, for the temporal test (unshadowed: r, g the sum of the luminances
//                   l_f, b of their squares, and out the mean's variance)
//                   (T_f = lum(E_f) D_f: the frame's ratio weight, what its shadow samples estimate the
//                   input lights add, D_f their mean weight; var(T_f) its variance, the frames independent)
//   heaviest frame  r: T_h, g: C_h of the frame with the largest D_f = T_f / C_f (C_f = lum(E_f), the
//                   irradiance T_f was drawn against); b, a: unused
// Raw, not filtered, values are summed so that the sums converge to the exact estimate instead of to
// a filtered one. Outputs, in place: the accumulated irradiance sum / N (with interleaving once
// N >= n^2, when the rotated dealing has given the pixel every light; before that stage 1 resolves the
// incomplete sums), the accumulated ratio sum(T r) / sum(T) (a ratio estimator,
// weighted as the a-trous filter weighs its taps) with the weight sum(T) / N in blue, that weight's
// variance in green and N in alpha for the filter, and the sampled irradiance
// lum(sum E / N), the mean of the irradiances the frames' T were drawn against (unresolved: with
// interleaving the tiles the pixel has seen, which before N >= n^2 are not all of them), so that the
// filter's mean weight sum(T) / sum(lum E) compares the same lights' sums.
// The weight's variance is the larger of the frames' own, sum(var T) / N^2, and the part of what the
// heaviest frame alone adds to the mean's squared error that its own variance cannot show,
// (T_h - D C_h)^2 / (k N^2) with D = sum T / sum C: a frame whose T rests on one heavy sample W among its
// k deviates by about W / k, while its samples' spread gives var(T_f) about (k - 1) W^2 / k^3, all but
// 1 / k of that squared deviation. With k = 1 a frame's var(T_f) is the prior alone, so an estimate
// resting on one heavy sample was trusted as typical (measured: 16 frames at 4 x 4, k = 1, the correction
// 2.5x the uncorrected error); the whole residual at k = 4 also held what a tile's lights add, and cost
// Sponza 10K's 4 x 4 16 frames 4% (docs/measurements.md). The frames' whole spread as a ratio
// estimator's, sum (T_f - D C_f)^2 / (N (N - 1)), also held what the tiles' lights add, which the rotated
// dealing stratifies, and took back half the correction's gain at 16 frames (Sponza 10K 4x4 k = 16 raw:
// 0.086 -> 0.121, the heaviest frame alone 0.088; uncorrected 0.151).
// With N = 1 the outputs are this frame's values bit for bit (unshadowed, the ratio image takes the moments).
// Under motion (the lights or the geometry moved since the last frame; docs/design.md §6, "history under
// motion"), the reprojected history is first tested (historyKept): kMotionGradient gives the irradiance's
// sums way to this frame's and scales the whole history by what the pixel's temporal tests keep;
// kMotionRatio replaces the irradiance's sums by this frame's and keeps the ratio's (the LGH paper's choice);
// kMotionKeep keeps the history as it is (SVGF's temporal accumulation: an exponential moving average of
// weight 1 / maxFrames once full, which lags a change by its length).
// Stage 1 (interleaving, 2 <= N < n^2): the pixel's sum covers N of the n^2 tiles' lights, so its
// irradiance is resolved from its neighbours' new sums, edge-aware as interleave_resolve.comp does, over
// the interleaving window for N frames (shared/interleave_window.glsl: n x n for N < n, a column of n
// rows from N >= n on).
#include "shared/bindings.h"
#include "shared/color.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/interleave_window.glsl"
#include "shared/accumulation_types.h"

layout(binding = LGH_TEXTURE_ACCUM_RAW_IRRADIANCE) uniform sampler2D rawIrradiance;  // tiled layout when n > 1
layout(binding = LGH_TEXTURE_ACCUM_IRRADIANCE_SUM) uniform sampler2D historyIrradiance;
layout(binding = LGH_TEXTURE_ACCUM_RATIO_SUM) uniform sampler2D historyRatio;
layout(binding = LGH_TEXTURE_ACCUM_HEAVIEST) uniform sampler2D historyHeaviest;
layout(binding = LGH_TEXTURE_ACCUM_RAW_RATIO) uniform sampler2D rawRatios;  // under motion: the ratio image's copy
layout(binding = LGH_TEXTURE_ACCUM_PREVIOUS_POSITION) uniform sampler2D previousPosition;  // w = 0: no surface
layout(binding = LGH_TEXTURE_ACCUM_PREVIOUS_NORMAL) uniform sampler2D previousNormal;
layout(rgba32f, binding = LGH_IMAGE_ACCUM_IRRADIANCE) uniform image2D irradiance;  // resolved in, accumulated out
layout(rgba32f, binding = LGH_IMAGE_ACCUM_RATIO) uniform image2D ratio;            // raw in, accumulated out (a: N)
layout(rgba32f, binding = LGH_IMAGE_ACCUM_IRRADIANCE_SUM) uniform writeonly image2D irradianceSumOut;
layout(rgba32f, binding = LGH_IMAGE_ACCUM_RATIO_SUM) uniform writeonly image2D ratioSumOut;
layout(rg32f, binding = LGH_IMAGE_ACCUM_HEAVIEST) uniform writeonly image2D heaviestOut;
layout(rgba32f, binding = LGH_IMAGE_ACCUM_POSITION) uniform writeonly image2D positionOut;
layout(rgba16f, binding = LGH_IMAGE_ACCUM_NORMAL) uniform writeonly image2D normalOut;
layout(r32f, binding = LGH_IMAGE_ACCUM_SAMPLED_IRRADIANCE) uniform writeonly image2D sampledIrradiance;  // C out

layout(std140, binding = LGH_UBO_PASS) uniform Accumulation { AccumulationUniforms accum; };

ivec2 tiledCoord(ivec2 pixel) {
  uvec2 p = uvec2(pixel);
  return ivec2((p % accum.tilesPerAxis) * uvec2(accum.tileWidth, accum.tileHeight) + p / accum.tilesPerAxis);
}

// The history pixel holding this surface, or (-1, -1) when the previous frame did not see it.
ivec2 historyPixel(Surface s, ivec2 size) {
  vec4 clip = accum.previousViewProjection * vec4(s.position - accum.previousCameraPosition, 1.0);
  if (clip.w <= 0.0) return ivec2(-1);
  // Nearest texel: a still camera maps every pixel centre onto itself, so the history is not blurred.
  ivec2 q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return ivec2(-1);
  vec4 p = texelFetch(previousPosition, q, 0);
  if (p.w == 0.0) return ivec2(-1);
  float footprint = max(distance(frame.cameraPosition.xyz, s.position) * frame.sceneScale.z, 1e-30);
  if (abs(dot(s.normal, p.xyz - s.position)) > accum.planeTolerance * footprint) return ivec2(-1);  // disoccluded
  if (dot(s.normal, texelFetch(previousNormal, q, 0).xyz) < accum.normalTolerance) return ivec2(-1);
  return q;
}

// kMotionGradient: what a frame in which something moved keeps of a pixel's history, from temporal tests
// that are 1 where the lighting at the surface has not changed and 0 where it has (x: the irradiance's
// history, y: the whole history's):
//  - x, the unshadowed irradiance's gradient |C_t - C_t-1| / max(C_t, C_t-1) over the resolved luminances
//    of this frame and the last (A-SVGF's normalised temporal gradient, Schied et al. 2018): its VPLs are
//    drawn from the same random numbers in both frames, so a change is the lighting's, not noise; the
//    irradiance's history gives way to this frame's linearly as the gradient reaches `motionTolerance`.
//    Only the irradiance's: this frame's is known whole (the light pass evaluates every VPL), so a moved
//    light costs the ratio's history nothing where its shadows stay. Where this frame's irradiance is
//    whole (the LGH without interleaving: every grid light at every pixel) it replaces the history's
//    outright; with n x n interleaving the history holds the other tiles' lights, and with the lightcuts'
//    ratio form other samples, worth keeping where unchanged;
//  - y, the visibility ratio, which k shadow samples a frame make noisy: the history's ratio R against
//    this frame's around the pixel, r_t = sum w T r / sum w T over the 5 x 5 pixels on the same surface
//    (w: normal and tangent plane as the history's own test), z = |r_t - R| / sqrt(var r_t + var R) with
//    var r_t = sum (w T)^2 / (sum w T)^2 / (4k) (k Bernoulli samples a pixel at their widest), kept whole
//    to z = 1.5 and dropped from z = 3 on. A pixel's k samples alone tell a lagging history only when its
//    shadow flips; the window's 25 k tell a drift of a tenth. The thresholds trade ghosts for flicker
//    (measured, MotionTest.JumpingOccluder… and the moving lamp's temporal error: z 2 to 4 left 1.44x the
//    fresh frame's error after a jump at 0.56x the flicker of no history; 1.5 to 3, 1.12x at 0.58x; 1 to 2,
//    0.98x at 0.62x);
//  - unshadowed (the lightcuts' shadowed estimate, one noisy value): y from the same z test of the frame's
//    luminance l_t against the history's mean and spread, x = y (a history of one frame, which has no
//    spread, kept below a gradient of 1/2; the LGH's unshadowed irradiance, whole, none).
vec2 historyKept(ivec2 pixel, Surface s, vec4 irradianceSum, vec4 ratioSum, float resolved, float l, bool shadowed) {
  float n = irradianceSum.a;
  if (n < 0.5) return vec2(1.0);
  float previous = ratioSum.a, largest = max(resolved, previous);
  float gradient = largest > 0.0 ? abs(resolved - previous) / largest : 0.0;
  float irradianceKept = clamp(1.0 - gradient / accum.motionTolerance, 0.0, 1.0);
  // A whole irradiance (every light at every pixel) is all there is to know of the frame's: its history
  // adds nothing, and gives way to it outright.
  if (accum.irradianceWhole != 0u) irradianceKept = 0.0;
  if (!shadowed) {
    if (accum.irradianceWhole != 0u) return vec2(0.0);
    // One frame has no spread to judge a change by: kept unless the luminance changed by half, so that a
    // noisy estimate's history can grow to the two frames the z test needs under continuous motion.
    if (n < 1.5) return vec2(gradient <= 0.5 ? 1.0 : 0.0);
    float mean = ratioSum.g / n;
    float spread = max(ratioSum.b / n - mean * mean, 0.0) * (1.0 + 1.0 / n);
    float z = abs(l - mean) / sqrt(max(spread, 1e-30 * mean * mean + 1e-37));
    return vec2(clamp((3.0 - z) / 1.5, 0.0, 1.0));
  }
  vec2 kept = vec2(irradianceKept, 1.0);
  if (ratioSum.g <= 0.0) return kept;
  float footprint = max(distance(frame.cameraPosition.xyz, s.position) * frame.sceneScale.z, 1e-30);
  float weighted = 0.0, weights = 0.0, squares = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(frame.resolution.xy)))) continue;
      Surface n = loadSurface(q);
      if (!n.valid || dot(n.normal, s.normal) < accum.normalTolerance ||
          abs(dot(s.normal, n.position - s.position)) > accum.planeTolerance * footprint)
        continue;
      vec4 raw = texelFetch(rawRatios, q, 0);
      float w = max(raw.b, 0.0);
      weighted += w * raw.r;
      weights += w;
      squares += w * w;
    }
  }
  if (weights <= 0.0) return kept;
  float history = ratioSum.r / ratioSum.g;
  float variance = squares / (weights * weights) * 0.25 / float(accum.shadowSamples) +
                   ratioSum.b / (ratioSum.g * ratioSum.g);
  float z = abs(weighted / weights - history) / sqrt(max(variance, 1e-30));
  kept.y = clamp((3.0 - z) / 1.5, 0.0, 1.0);
  return kept;
}

// Stage 1: the irradiance of a pixel whose sum lacks some tiles, from the window's new sums (bound as
// historyIrradiance).
void resolveIncomplete(ivec2 pixel) {
  Surface s = loadSurface(pixel);
  float frames = texelFetch(historyIrradiance, pixel, 0).a;
  uint n = accum.tilesPerAxis;
  if (!s.valid || frames < 1.5 || frames >= float(n * n)) return;
  ivec2 halfWidths = interleaveHalfWidths(n, frames);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int dy = -halfWidths.y; dy <= halfWidths.y; ++dy) {
    for (int dx = -halfWidths.x; dx <= halfWidths.x; ++dx) {
      float w = interleaveTapWeight(s, pixel, ivec2(dx, dy), n, halfWidths, accum.normalPower, accum.planeSigma);
      vec4 qSum = w > 0.0 ? texelFetch(historyIrradiance, pixel + ivec2(dx, dy), 0) : vec4(0.0);
      if (qSum.a == 0.0) continue;
      sum += w * qSum.rgb / qSum.a;
      weightSum += w;
    }
  }
  // The pixel's own tap has weight 1.
  imageStore(irradiance, pixel, vec4(sum / weightSum, imageLoad(irradiance, pixel).a));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.resolution.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  if (accum.stage == kAccumulateResolveIncomplete) {
    resolveIncomplete(pixel);
    return;
  }
  Surface s = loadSurface(pixel);
  imageStore(positionOut, pixel, vec4(s.position, s.valid ? 1.0 : 0.0));
  imageStore(normalOut, pixel, vec4(s.normal, 0.0));
  if (!s.valid) {
    imageStore(irradianceSumOut, pixel, vec4(0.0));
    imageStore(ratioSumOut, pixel, vec4(0.0));
    imageStore(heaviestOut, pixel, vec4(0.0));
    return;
  }
  vec4 irradianceSum = vec4(0.0), ratioSum = vec4(0.0), heaviest = vec4(0.0);
  if (accum.hasHistory != 0u) {
    ivec2 q = historyPixel(s, size);
    if (q.x >= 0) {
      irradianceSum = texelFetch(historyIrradiance, q, 0);
      ratioSum = texelFetch(historyRatio, q, 0);
      heaviest = texelFetch(historyHeaviest, q, 0);
    }
  }
  vec3 e = accum.tilesPerAxis > 1u ? texelFetch(rawIrradiance, tiledCoord(pixel), 0).rgb
                                   : texelFetch(rawIrradiance, pixel, 0).rgb;
  vec4 rawRatio = imageLoad(ratio, pixel);
  float l = max(luminance(e), 0.0);
  bool shadowed = accum.shadowSamples != 0u;
  vec3 resolvedIrradiance = imageLoad(irradiance, pixel).rgb;  // this frame's, resolved
  float resolved = max(luminance(resolvedIrradiance), 0.0);
  // The irradiance's history given way to this frame's (resolved: with interleaving, its tile alone would
  // be a noisy part) in the share `replaced`; then the whole history scaled to what is kept.
  float replaced = accum.motion == kMotionRatio ? 1.0 : 0.0;
  if (accum.motion == kMotionGradient) {
    vec2 kept = historyKept(pixel, s, irradianceSum, ratioSum, resolved, l, shadowed);
    replaced = 1.0 - kept.x;
    irradianceSum *= kept.y;
    ratioSum *= kept.y;
    if (kept.y == 0.0) heaviest = vec4(0.0);
  }
  // The ratio's weights T were drawn against the irradiance they replace: scaled with it, so that their mean
  // weight D = sum T / sum C (what the correction multiplies the irradiance by) stays what the samples said.
  float replacedLuminance = luminance(irradianceSum.rgb);
  irradianceSum.rgb = mix(irradianceSum.rgb, resolvedIrradiance * irradianceSum.a, replaced);
  if (replaced > 0.0 && replacedLuminance > 0.0) {
    float scale = max(luminance(irradianceSum.rgb), 0.0) / replacedLuminance;
    ratioSum.rgb *= vec3(scale, scale, scale * scale);
    heaviest.rg *= scale;
  }
  // At the cap the sums are scaled to maxFrames - 1 frames first: a moving average of the last frames.
  float n = irradianceSum.a;
  if (n > accum.maxFrames - 1.0) {
    float keep = (accum.maxFrames - 1.0) / n;
    irradianceSum *= keep;
    ratioSum *= keep;
  }
  float r = shadowed ? rawRatio.r : 1.0, weight = shadowed ? max(rawRatio.b, 0.0) : l;
  float variance = shadowed ? max(rawRatio.g, 0.0) : l * l;  // unshadowed: the luminance's second moment
  irradianceSum += vec4(e, 1.0);
  ratioSum += vec4(weight * r, weight, variance, 0.0);
  ratioSum.a = resolved;
  if (l > 0.0 && (heaviest.g <= 0.0 || weight * heaviest.g > heaviest.r * l)) heaviest = vec4(weight, l, 0.0, 0.0);
  imageStore(irradianceSumOut, pixel, irradianceSum);
  imageStore(ratioSumOut, pixel, ratioSum);
  imageStore(heaviestOut, pixel, heaviest);
  float frames = irradianceSum.a;
  if (!shadowed) {
    // The luminance's temporal moments, for a filter guided by the estimate's variance (the lightcuts'):
    // the accumulated mean's variance, (sum l^2 - (sum l)^2 / N) / (N (N - 1)), in green (0 while N = 1),
    // N in alpha.
    float spread = max(ratioSum.b - ratioSum.g * ratioSum.g / frames, 0.0);
    imageStore(ratio, pixel, vec4(1.0, frames > 1.5 ? spread / (frames * (frames - 1.0)) : 0.0, ratioSum.g / frames, frames));
  }
  if (frames < 1.5) return;  // this frame only: its values stay as they are
  // Before n^2 frames the sum lacks some of the lights' tiles: stage 1 resolves it.
  if (frames >= float(accum.tilesPerAxis * accum.tilesPerAxis))
    imageStore(irradiance, pixel, vec4(irradianceSum.rgb / frames, imageLoad(irradiance, pixel).a));
  if (shadowed) {
    // sum(T) = 0: no frame's samples weighed anything, and each frame's ratio was 1 (shadow_rays.comp).
    float accumulated = ratioSum.g > 0.0 ? ratioSum.r / ratioSum.g : rawRatio.r;
    float irradianceLuminance = luminance(irradianceSum.rgb);  // sum C
    float meanWeight = irradianceLuminance > 0.0 ? ratioSum.g / irradianceLuminance : 1.0;  // D
    float residual = heaviest.r - meanWeight * heaviest.g;
    float heaviestShare = residual * residual / (float(accum.shadowSamples) * frames * frames);
    if (isnan(heaviestShare)) heaviestShare = uintBitsToFloat(0x7f800000u);  // sum C underflows: D is unknown
    float weightVariance = max(ratioSum.b / (frames * frames), heaviestShare);
    imageStore(ratio, pixel, vec4(clamp(accumulated, 0.0, 1.0), weightVariance, ratioSum.g / frames, frames));
    imageStore(sampledIrradiance, pixel, vec4(luminance(irradianceSum.rgb / frames)));
  }
}
