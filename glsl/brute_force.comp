#version 450 core
// The exact unshadowed sum over every input light at every pixel (weight 1, same shading and clamp as
// the light pass): the value the LGH light pass approximates, computed without rasterization so that
// it checks the light pass rather than repeating it. Adds into `irradianceOut`, so C++ can feed lights
// one storage block at a time. With LGH_SHADOWED every light's contribution is multiplied by its
// visibility (one shadow ray per light per pixel): the exact shadowed reference, for small images.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/lgh_shading.glsl"
#include "shared/lgh_types.h"
#include "shared/octahedral.h"
#ifdef LGH_SHADOWED
#include "shared/bvh_traverse.glsl"
#include "shared/ray_offset.h"
#endif

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight lights[]; };
layout(rgba32f, binding = LGH_IMAGE_BRUTE_FORCE_IRRADIANCE) uniform image2D irradianceOut;
uniform uint lightCount;
uniform float clampDistance;

const uint kBatch = 64u;
shared vec3 batchPosition[kBatch];
shared vec3 batchIntensity[kBatch];
shared vec4 batchLobe[kBatch];  // xyz normal, w omni fraction

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  bool inside = all(lessThan(pixel, ivec2(frame.resolution.xy)));
  Surface s = loadSurface(min(pixel, ivec2(frame.resolution.xy) - 1));
  vec3 total = vec3(0.0);
  // Every invocation takes part in loading the batches (barriers), shading only where it has a surface.
  for (uint first = 0u; first < lightCount; first += kBatch) {
    uint i = first + gl_LocalInvocationIndex;
    if (i < lightCount) {
      GpuLight l = lights[i];
      batchPosition[gl_LocalInvocationIndex] = l.position;
      batchIntensity[gl_LocalInvocationIndex] = l.intensity;
      bool oriented = (l.flags & kLightOriented) != 0u;
      batchLobe[gl_LocalInvocationIndex] = oriented ? vec4(octDecode(l.normalOct), 0.0) : vec4(0.0, 0.0, 0.0, 1.0);
    }
    barrier();
    if (inside && s.valid) {
      vec3 batchSum = vec3(0.0);  // summed per batch first: less rounding over a million lights
      uint n = min(kBatch, lightCount - first);
      for (uint j = 0u; j < n; ++j) {
        vec3 e = lightContribution(batchPosition[j], batchIntensity[j], batchLobe[j].xyz, batchLobe[j].w,
                                   s.position, s.normal, clampDistance);
#ifdef LGH_SHADOWED
        if (all(equal(e, vec3(0.0)))) continue;
        // The same ray the shadow pass would trace to an unjittered light.
        vec3 origin = offsetRayOrigin(s.position, s.normal);
        vec3 toLight = batchPosition[j] - origin;
        float d = length(toLight);
        if (d > 0.0 && traceAnyHit(origin, toLight / d, 0.0, d * (1.0 - 1e-3))) continue;
#endif
        batchSum += e;
      }
      total += batchSum;
    }
    barrier();
  }
  if (inside) imageStore(irradianceOut, pixel, imageLoad(irradianceOut, pixel) + vec4(total, 0.0));
}
