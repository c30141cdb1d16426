// How linear images become display values, written once for image files (render/image_io.cpp,
// render/renderer.cpp) and the viewer's display pass (glsl/display.frag): a viewer screenshot and an
// lgh-render PNG of the same frame then differ by 8-bit rounding only.
#ifndef LGH_DISPLAY_ENCODE_H
#define LGH_DISPLAY_ENCODE_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

// Tone curves, in the order of lgh::ToneMap (render/image_io.h).
GPU_CONST uint kToneMapClamp = 0u;
GPU_CONST uint kToneMapReinhard = 1u;
GPU_CONST uint kToneMapAces = 2u;

GPU_FUNC float srgbEncode(float linear) {
  linear = clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * pow(linear, 1.0f / 2.4f) - 0.055f;
}

// What an image holds, which decides how it is shown (the viewer's DisplayPass) and written
// (lgh-render, Renderer::readImage): radiance gets exposure, a tone curve and sRGB; data (albedo,
// normals, ...) is clamped to [0, 1] and sRGB-encoded; a ratio is its r channel as grey data; fragment
// counts become a heat map over the frame's largest count.
GPU_CONST uint kDisplayRadiance = 0u;
GPU_CONST uint kDisplayData = 1u;
GPU_CONST uint kDisplayRatio = 2u;
GPU_CONST uint kDisplayCounts = 3u;
GPU_CONST uint kDisplayHistory = 4u;  // the history length in alpha, a heat map over largestCount

// Exposure (EV), tone curve and the sRGB transfer function: linear radiance to [0, 1].
GPU_FUNC vec3 encodeForDisplay(vec3 linear, float exposureEV, uint toneCurve) {
  vec3 c = max(linear, vec3(0.0f)) * exp2(exposureEV);
  if (toneCurve == kToneMapReinhard) c = c / (vec3(1.0f) + c);
  if (toneCurve == kToneMapAces)  // Narkowicz's fit of the ACES filmic curve
    c = (c * (2.51f * c + 0.03f)) / (c * (2.43f * c + 0.59f) + 0.14f);
  return vec3(srgbEncode(c.x), srgbEncode(c.y), srgbEncode(c.z));
}

// A perceptual heat map (magma-like: black, purple, orange, pale yellow) of t in [0, 1], for the
// light pass's fragments per pixel (the paper's Fig. 5).
GPU_FUNC vec3 heatStop(int i) {
  return i == 0   ? vec3(0.0f, 0.0f, 0.02f)
         : i == 1 ? vec3(0.23f, 0.06f, 0.44f)
         : i == 2 ? vec3(0.55f, 0.16f, 0.51f)
         : i == 3 ? vec3(0.87f, 0.32f, 0.38f)
         : i == 4 ? vec3(0.99f, 0.62f, 0.36f)
                  : vec3(0.99f, 0.99f, 0.75f);
}
GPU_FUNC vec3 heatColor(float t) {
  float x = clamp(t, 0.0f, 1.0f) * 5.0f;
  int i = min(int(x), 4);
  vec3 a = heatStop(i);
  return a + (heatStop(i + 1) - a) * (x - float(i));
}

GPU_NAMESPACE_END
#endif
