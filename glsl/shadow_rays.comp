#version 450 core
// One shadow ray per selected light per pixel (docs/design.md §5): from the pixel's surface to the light,
// jittered inside its cluster, any-hit through the scene BVH. Writes the raw visibility ratio: the
// mean of the k visibilities (importance selection, each sample already drawn in proportion to its
// contribution) or the contribution-weighted mean (uniform selection).
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/color.glsl"
#include "shared/bindings.h"
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/bvh_traverse.glsl"
#include "shared/lgh_shading.glsl"
#include "shared/lgh_types.h"
#include "shared/light_levels.h"
#include "shared/light_pass_types.h"
#include "shared/octahedral.h"
#include "shared/ray_offset.h"
#include "shared/sampling.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight inputLights[]; };
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer ShadowSlots { uint shadowSlots[]; };
layout(std430, binding = LGH_BINDING_PASS3) readonly buffer GridLights { GpuGridLight gridLights[]; };
layout(rgba32f, binding = LGH_IMAGE_SHADOW_RATIO) uniform writeonly image2D ratioOut;  // r: visibility ratio, g: rays traced

uniform uint samples;        // k
uniform uint tilesPerAxis;   // the slots are in the light pass's (tiled) layout
uniform uvec2 tileSize;
uniform float spread;        // jitter scale: the jitter's standard deviation is spread x the cluster's
uniform int uniformSelection;
uniform float clampDistance;
// For uniform selection's weights: the blending parameters of the light pass.
uniform float alpha;
uniform float topCellSize;
uniform uint firstLevel;
uniform uint levels;
uniform int bruteForce;
uniform uint frameSeed;

// Raised-cosine variate on [-1, 1], pdf (1 + cos(pi s)) / 2, by Newton's method on its CDF
// (s + 1) / 2 + sin(pi s) / (2 pi); four steps from a good start reach float precision.
float raisedCosine(float u) {
  float s = 2.0 * u - 1.0;
  s = sign(s) * (1.0 - sqrt(1.0 - abs(s)));  // the CDF's shape near the ends
  for (int i = 0; i < 4; ++i) {
    float f = 0.5 * (s + 1.0) + sin(kPi * s) / (2.0 * kPi) - u;
    float df = 0.5 * (1.0 + cos(kPi * s));
    s = clamp(s - f / max(df, 1e-6), -1.0, 1.0);
  }
  return s;
}
const float kRaisedCosineStd = 0.36151;  // sqrt(1/3 - 2/pi^2)

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.resolution.xy)))) return;
  Surface s = loadSurface(pixel);
  uvec2 p = uvec2(pixel);
  uvec2 tiled = (p % tilesPerAxis) * tileSize + p / tilesPerAxis;
  uint pixelIndex = tiled.y * (tilesPerAxis * tileSize.x) + tiled.x;
  float visible = 0.0, weights = 0.0, rays = 0.0;
  if (s.valid) {
    vec3 origin = offsetRayOrigin(s.position, s.normal);
    Rng rng = makeRng(pixelIndex, frameSeed ^ 0x5bd1e995u);
    for (uint j = 0u; j < samples; ++j) {
      uint id = shadowSlots[pixelIndex * samples + j];
      if (id == kNoLight) continue;
      vec3 sigma = vec3(0.0);
      ShadedLight light;
      if ((id & kSlotS0) != 0u) {
        light = decodeInputLight(inputLights[id & ~kSlotS0]);
      } else {
        light = decodeGridLight(gridLights[id]);
        sigma = sqrt(max(gridLights[id].variance, vec3(0.0)));
      }
      vec3 lightPosition = light.position;
      float weight = 1.0;
      if (uniformSelection != 0) {
        // Uniform selection: weight each visibility by the light's contribution here.
        float R = levelRadius(alpha, topCellSize, light.level, levels);
        uint role = bruteForce != 0 ? kRoleOnly : levelRole(light.level, firstLevel, levels);
        vec3 e = blendWeight(role, distance(lightPosition, s.position), R) *
                 lightContribution(lightPosition, light.intensity, light.meanNormal, light.omniFraction, s.position,
                                   s.normal, clampDistance);
        weight = luminance(e);
      }
      vec3 jitter = vec3(raisedCosine(nextFloat(rng)), raisedCosine(nextFloat(rng)), raisedCosine(nextFloat(rng)));
      vec3 target = lightPosition + (spread / kRaisedCosineStd) * sigma * jitter;
      vec3 toLight = target - origin;
      float d = length(toLight);
      // Stop short of the light by a relative margin: VPLs sit on surfaces, and so may a cluster's centre.
      bool blocked = d > 0.0 && traceAnyHit(origin, toLight / d, 0.0, d * (1.0 - 1e-3));
      visible += weight * (blocked ? 0.0 : 1.0);
      weights += weight;
      rays += 1.0;
    }
  }
  // No selected light (nothing lights this pixel through the LGH): visibility 1 multiplies zero anyway.
  float ratio = weights > 0.0 ? visible / weights : 1.0;
  imageStore(ratioOut, pixel, vec4(ratio, rays, 0.0, 1.0));
}
