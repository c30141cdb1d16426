// One a-trous pass's taps (Dammertz et al. 2010): a 5 x 5 B3-spline kernel with holes of `stepSize`
// pixels, each tap weighted by how much its surface looks like the centre's (normal, tangent-plane
// distance) and by a signal stop its caller computes. The shadow filter (atrous.comp: the ratio's stop)
// and the lightcuts' filter (irradiance_atrous.comp: the luminance's, scaled by its standard deviation)
// use these taps. Needs shared/gbuffer.glsl and shared/frame.glsl.
#ifndef LGH_ATROUS_TAPS_GLSL
#define LGH_ATROUS_TAPS_GLSL

// The B3 spline (1/16, 1/4, 3/8, 1/4, 1/16) by |offset|.
const float kAtrousKernel[3] = float[](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

// The world-space length the tangent-plane distance is measured in: a pixel's footprint at s, times the holes.
float atrousFootprint(Surface s, int stepSize) {
  return max(distance(frame.cameraPosition.xyz, s.position) * frame.sceneScale.z, 1e-30) * float(stepSize);
}

// The tap at `offset` x stepSize from `pixel`, or false where it is off the image or shows no surface.
bool atrousTap(ivec2 pixel, ivec2 offset, int stepSize, out ivec2 q, out vec4 qPosition) {
  q = pixel + offset * stepSize;
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(frame.resolution.xy)))) return false;
  qPosition = texelFetch(gPosition, q, 0);
  return qPosition.w != 0.0;
}

// The tap's weight: kernel x max(0, n.n')^normalPower x exp(-(plane^2 + stop) / 2), plane the tap's
// distance from s's tangent plane in footprints x planeSigma; `stop` is the caller's signal term (a
// squared difference over sigma^2 for a Gaussian stop, 2 |difference| / scale for SVGF's exponential one).
float atrousTapWeight(Surface s, ivec2 offset, ivec2 q, vec4 qPosition, float footprint, float normalPower,
                      float planeSigma, float stop) {
  float plane = abs(dot(s.normal, qPosition.xyz - s.position)) / (footprint * planeSigma);
  return kAtrousKernel[abs(offset.x)] * kAtrousKernel[abs(offset.y)] *
         pow(max(0.0, dot(s.normal, texelFetch(gNormal, q, 0).xyz)), normalPower) * exp(-0.5 * (plane * plane + stop));
}

#endif
