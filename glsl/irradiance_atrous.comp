#version 450 core
// Edge-avoiding a-trous wavelet filter (Dammertz et al. 2010) of an irradiance estimate that carries its
// own shadows: the stochastic lightcuts' (rtslc.comp), which has no noise-free unshadowed irradiance to
// filter a ratio against (atrous.comp). The same kernel, passes, normal and plane weights as the LGH's
// shadow filter, so that both methods are compared filtered on equal terms (docs/design.md §12); the
// ratio's edge-stopping becomes the relative luminance difference (l' - l) / max(l, l'), in [-1, 1] as a
// ratio difference is, from the second pass on (the first sees one frame's raw samples, whose
// differences are noise). Over N accumulated frames the luminance sigma shrinks as N^-sigmaFade and the
// floor(sigmaFade log2 N) widest passes are skipped, as the shadow filter does.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/color.glsl"
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/irradiance_filter_types.h"

layout(binding = LGH_TEXTURE_FILTER_SIGNAL) uniform sampler2D signalIn;
layout(rgba32f, binding = LGH_IMAGE_FILTER_OUT) uniform writeonly image2D signalOut;
layout(std140, binding = LGH_UBO_PASS) uniform IrradianceFilter { IrradianceFilterUniforms filtering; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.resolution.xy);
  if (any(greaterThanEqual(pixel, size))) return;
  vec4 centre = texelFetch(signalIn, pixel, 0);
  Surface s = loadSurface(pixel);
  int kept = filtering.passes - int(floor(filtering.sigmaFade * log2(max(filtering.frames, 1.0))));
  if (!s.valid || filtering.stepSize >= (1 << clamp(kept, 0, 30))) {  // no surface, or a pass skipped at N frames
    imageStore(signalOut, pixel, centre);
    return;
  }
  const float kernel[3] = float[](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
  float footprint =
      max(distance(frame.cameraPosition.xyz, s.position) * frame.sceneScale.z, 1e-30) * float(filtering.stepSize);
  float sigma = filtering.luminanceSigma * pow(max(filtering.frames, 1.0), -filtering.sigmaFade);
  float centreLuminance = luminance(centre.rgb);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = pixel + ivec2(dx, dy) * filtering.stepSize;
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 qPosition = texelFetch(gPosition, q, 0);
      if (qPosition.w == 0.0) continue;
      vec3 v = texelFetch(signalIn, q, 0).rgb;
      float l = luminance(v), largest = max(l, centreLuminance);
      float plane = abs(dot(s.normal, qPosition.xyz - s.position)) / (footprint * filtering.planeSigma);
      // Not between two all but black taps: llvmpipe flushes denormals in arithmetic but not in comparisons,
      // so largest > 0 could still divide 0 by 0.
      float dl = filtering.stepSize > 1 && largest > 1e-30 ? (l - centreLuminance) / (largest * sigma) : 0.0;
      float w = kernel[abs(dx)] * kernel[abs(dy)] *
                pow(max(0.0, dot(s.normal, texelFetch(gNormal, q, 0).xyz)), filtering.normalPower) *
                exp(-0.5 * (plane * plane + dl * dl));
      sum += w * v;
      weightSum += w;
    }
  }
  // The centre tap has weight (3/8)^2 > 0.
  imageStore(signalOut, pixel, vec4(sum / weightSum, centre.a));
}
