// The window that puts n x n interleaved tiles back together (docs/design.md §4, "Interleaving"): a
// pixel averages its neighbours over a box of width n with half-weight ends (n + 1 taps per axis when
// n is even, so each tile class is counted exactly once and the window is symmetric), each weighted by
// how much its surface looks like the pixel's own. The irradiance's resolve (interleave_resolve.comp),
// the accumulation's resolve of incomplete sums (accumulate.comp) and the shadow filter's resolve of
// the ratio and its weights (atrous.comp) use this one window, so that what they divide by each other
// covers the same tiles. Needs shared/gbuffer.glsl and shared/frame.glsl.
#ifndef LGH_INTERLEAVE_WINDOW_GLSL
#define LGH_INTERLEAVE_WINDOW_GLSL

// The window's half-widths (x, y) for a pixel whose estimate holds `frames` accumulated frames of
// n x n tiles dealt in rotation, one class further per frame: N consecutive frames give a pixel N
// consecutive classes and the neighbour dy rows away sees them shifted by n dy, so for N < n the
// n x n window counts every class N times, from N >= n on a vertical window of n rows covers every
// class (exactly floor(N / n) or one more times), and from N >= n^2 the pixel alone holds them all.
ivec2 interleaveHalfWidths(uint n, float frames) {
  int half_ = int(n / 2u);
  if (n <= 1u || frames >= float(n * n)) return ivec2(0);
  return ivec2(frames >= float(n) ? 0 : half_, half_);
}

// How much the surface at pixel q looks like s: max(0, n.n')^normalPower times the Gaussian of q's
// distance from s's tangent plane in pixel footprints (sigma planeSigma); 0 off the image or on background.
float surfaceSimilarity(Surface s, ivec2 q, float normalPower, float planeSigma) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(frame.resolution.xy)))) return 0.0;
  vec4 qPosition = texelFetch(gPosition, q, 0);
  if (qPosition.w == 0.0) return 0.0;
  float footprint = max(distance(frame.cameraPosition.xyz, s.position) * frame.sceneScale.z, 1e-30);
  float plane = abs(dot(s.normal, qPosition.xyz - s.position)) / (footprint * planeSigma);
  return pow(max(0.0, dot(s.normal, texelFetch(gNormal, q, 0).xyz)), normalPower) * exp(-0.5 * plane * plane);
}

// The weight of the neighbour at `offset` (|offset| within the half-widths) for the surface s: the box's
// end weights (1, 1/2 or 1/4: exact factors) times its surface similarity.
float interleaveTapWeight(Surface s, ivec2 pixel, ivec2 offset, uint n, ivec2 halfWidths, float normalPower,
                          float planeSigma) {
  bool even = (n & 1u) == 0u;
  int half_ = int(n / 2u);
  float window = (even && halfWidths.x == half_ && abs(offset.x) == half_ ? 0.5 : 1.0) *
                 (even && halfWidths.y == half_ && abs(offset.y) == half_ ? 0.5 : 1.0);
  return window * surfaceSimilarity(s, pixel + offset, normalPower, planeSigma);
}

#endif
