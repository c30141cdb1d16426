#version 450 core
// Direct light from punctual lights (the scene's, or all but its point lights): exact, one ray-traced shadow ray per light per pixel.
#include "shared/bindings.h"
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/frame.glsl"
#include "shared/gbuffer.glsl"
#include "shared/bvh_traverse.glsl"
#include "shared/ray_offset.h"
#include "shared/punctual.glsl"

layout(std430, binding = LGH_BINDING_PUNCTUAL_LIGHTS) readonly buffer PunctualLights { GpuPunctualLight lights[]; };
layout(rgba32f, binding = LGH_IMAGE_DIRECT) uniform image2D directOut;
uniform uint firstLight;   // this dispatch shades lights [firstLight, firstLight + lightCount)
uniform uint lightCount;
uniform bool shadows;
uniform bool accumulate;   // add to what earlier dispatches wrote

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.resolution.xy)))) return;
  Surface s = loadSurface(pixel);
  vec3 radiance = vec3(0.0);
  if (s.valid) {
    vec3 origin = offsetRayOrigin(s.position, s.normal);
    for (uint i = firstLight; i < firstLight + lightCount; ++i) {
      LightSample ls = samplePunctual(lights[i], s.position, s.normal);
      if (ls.cosTheta <= 0.0 || all(equal(ls.irradiance, vec3(0.0)))) continue;
      if (shadows && traceAnyHit(origin, ls.direction, 0.0, ls.distance)) continue;
      radiance += s.albedo * (1.0 / 3.14159265358979) * ls.irradiance;
    }
  }
  if (accumulate) radiance += imageLoad(directOut, pixel).rgb;
  imageStore(directOut, pixel, vec4(radiance, 1.0));
}
