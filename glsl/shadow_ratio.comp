#version 450 core
// The shadow-ray pass's last step: each pixel's raw visibility ratio r = sum w V / sum w over its k slots,
// from the slot weights shadow_rays.comp wrote and shadow_trace.comp zeroed where a ray was blocked;
// sum w is in the ratio image's red, which r replaces. A pixel no selected light reaches (sum w = 0) gets
// r = 1: visibility multiplies zero there anyway.
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/bindings.h"
#include "shared/frame.glsl"
#include "shared/shadow_ray.glsl"
#include "shared/shadow_ray_types.h"

layout(std430, binding = LGH_BINDING_PASS7) readonly buffer SlotWeights { float slotWeights[]; };  // (y W + x) k + j
layout(rgba32f, binding = LGH_IMAGE_SHADOW_RATIO) uniform image2D ratio;  // r: sum w in, the ratio out
layout(std140, binding = LGH_UBO_PASS) uniform ShadowRays { ShadowRayUniforms rays; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.resolution.xy)))) return;
  uint first = shadowFirstSlot(uvec2(pixel), rays.samples);
  float visible = 0.0;
  for (uint j = 0u; j < rays.samples; ++j) visible += slotWeights[first + j];
  vec4 v = imageLoad(ratio, pixel);
  v.r = v.r > 0.0 ? visible / v.r : 1.0;
  imageStore(ratio, pixel, v);
}
