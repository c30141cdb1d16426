#version 450 core
// Final = emission + direct + indirect_unshadowed * visibility ratio, where the indirect radiance is
// albedo / pi x the light pass's irradiance (albedo applied here, after interleaving and filtering).
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
layout(binding = LGH_TEXTURE_COMPOSITE_DIRECT) uniform sampler2D directLight;
layout(binding = LGH_TEXTURE_COMPOSITE_INDIRECT) uniform sampler2D indirectIrradiance;  // LGH irradiance, unshadowed (black without GI)
layout(binding = LGH_TEXTURE_COMPOSITE_VISIBILITY) uniform sampler2D visibilityRatio; // filtered shadow ratio (r), 1 without shadows
layout(rgba32f, binding = LGH_IMAGE_COMPOSITE_FINAL) uniform writeonly image2D finalOut;
layout(rgba32f, binding = LGH_IMAGE_COMPOSITE_INDIRECT) uniform writeonly image2D indirectOut;  // unshadowed indirect radiance (AOV)
layout(std430, binding = LGH_BINDING_PASS0) buffer Counters { uint nonFinitePixels; };

// The optional inputs may be 1x1 stand-ins (black indirect, white visibility); texelFetch ignores wrap
// modes, so clamp the coordinate to the texture.
vec4 fetchClamped(sampler2D t, ivec2 p) { return texelFetch(t, min(p, textureSize(t, 0) - 1), 0); }

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.resolution.xy)))) return;
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec3 indirect = albedo * (1.0 / 3.14159265358979) * fetchClamped(indirectIrradiance, pixel).rgb;
  vec3 color = texelFetch(gEmission, pixel, 0).rgb + texelFetch(directLight, pixel, 0).rgb +
               indirect * fetchClamped(visibilityRatio, pixel).r;
  // Never let a NaN or Inf reach an image: the pixel is written black and counted, and the renderer
  // reports the count (tests require zero).
  if (any(isnan(color)) || any(isinf(color))) {
    color = vec3(0.0);
    atomicAdd(nonFinitePixels, 1u);
  }
  imageStore(finalOut, pixel, vec4(color, 1.0));
  imageStore(indirectOut, pixel, vec4(any(isnan(indirect)) || any(isinf(indirect)) ? vec3(0.0) : indirect, 1.0));
}
