#version 450 core
// A frame's image as display pixels, encoded as lgh-render encodes the same AOV for a PNG
// (shared/display_encode.h): the target is RGBA8 and the image is read 1:1.
#include "shared/bindings.h"
#include "shared/display_encode.h"

#ifdef LGH_DISPLAY_COUNTS
layout(binding = LGH_TEXTURE_DISPLAY_IMAGE) uniform usampler2D image;  // R32UI fragments per pixel
#else
layout(binding = LGH_TEXTURE_DISPLAY_IMAGE) uniform sampler2D image;
#endif
uniform uint encoding;      // kDisplayRadiance, kDisplayData, kDisplayRatio, kDisplayCounts, kDisplayHistory
uniform float exposureEV;   // radiance only
uniform uint toneCurve;     // radiance only: kToneMapClamp, kToneMapReinhard, kToneMapAces
uniform float largestCount; // counts and history only

layout(location = 0) out vec4 color;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef LGH_DISPLAY_COUNTS
  vec3 linear = heatColor(float(texelFetch(image, pixel, 0).r) / largestCount);
  color = vec4(encodeForDisplay(linear, 0.0, kToneMapClamp), 1.0);
#else
  vec4 value = texelFetch(image, pixel, 0);
  if (encoding == kDisplayRadiance)
    color = vec4(encodeForDisplay(value.rgb, exposureEV, toneCurve), 1.0);
  else if (encoding == kDisplayRatio)
    color = vec4(encodeForDisplay(vec3(value.r), 0.0, kToneMapClamp), 1.0);
  else if (encoding == kDisplayHistory)
    color = vec4(encodeForDisplay(heatColor(min(value.a / largestCount, 1.0)), 0.0, kToneMapClamp), 1.0);
  else
    color = vec4(encodeForDisplay(value.rgb, 0.0, kToneMapClamp), 1.0);
#endif
}
