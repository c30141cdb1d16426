// Irradiance from one KHR_lights_punctual light at a surface point.
#ifndef LGH_PUNCTUAL_GLSL
#define LGH_PUNCTUAL_GLSL
#include "shared/scene_types.h"

struct LightSample {
  vec3 direction;   // unit, surface to light
  float distance;   // to the light; +inf for directional lights
  float cosTheta;   // dot(surface normal, direction)
  vec3 irradiance;  // E = I cos(theta) / d^2 (point, spot) or E_perp cos(theta) (directional), 0 if cos <= 0
};

LightSample samplePunctual(GpuPunctualLight light, vec3 x, vec3 n) {
  LightSample ls;
  vec3 intensity = light.intensity;
  if (light.type == kLightDirectional) {
    ls.direction = -light.direction;
    ls.distance = uintBitsToFloat(0x7f800000u);
    ls.cosTheta = dot(n, ls.direction);
    ls.irradiance = intensity * max(ls.cosTheta, 0.0);
    return ls;
  }
  vec3 toLight = light.position - x;
  float d2 = max(dot(toLight, toLight), 1e-30);
  ls.distance = sqrt(d2);
  ls.direction = toLight / ls.distance;
  ls.cosTheta = dot(n, ls.direction);
  if (light.type == kLightSpot) {
    // glTF's smooth cone falloff: squared linear ramp in cos between the outer and inner cones.
    float cd = dot(light.direction, -ls.direction);
    float t = clamp((cd - light.outerConeCos) / max(light.innerConeCos - light.outerConeCos, 1e-4), 0.0, 1.0);
    intensity *= t * t;
  }
  if (light.range > 0.0) {
    // glTF's recommended range window, so lights with a range end smoothly.
    float r = ls.distance / light.range;
    float window = clamp(1.0 - r * r * r * r, 0.0, 1.0);
    intensity *= window * window;
  }
  ls.irradiance = intensity * max(ls.cosTheta, 0.0) / d2;
  return ls;
}
#endif
