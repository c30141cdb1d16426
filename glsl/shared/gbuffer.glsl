// G-buffer access for compute and fragment shaders. Texture units are fixed so every pass that
// reads the G-buffer binds it the same way (GBuffer::bindForReading).
#ifndef LGH_GBUFFER_GLSL
#define LGH_GBUFFER_GLSL
layout(binding = LGH_TEXTURE_GBUFFER_POSITION) uniform sampler2D gPosition;  // xyz world position, w = 1 on geometry, 0 on background
layout(binding = LGH_TEXTURE_GBUFFER_NORMAL) uniform sampler2D gNormal;    // xyz unit shading normal facing the camera
layout(binding = LGH_TEXTURE_GBUFFER_ALBEDO) uniform sampler2D gAlbedo;    // rgb linear diffuse albedo
layout(binding = LGH_TEXTURE_GBUFFER_EMISSION) uniform sampler2D gEmission;  // rgb emitted radiance

struct Surface {
  vec3 position;
  vec3 normal;
  vec3 albedo;
  bool valid;
};

Surface loadSurface(ivec2 pixel) {
  vec4 p = texelFetch(gPosition, pixel, 0);
  Surface s;
  s.position = p.xyz;
  s.valid = p.w > 0.0;
  s.normal = texelFetch(gNormal, pixel, 0).xyz;
  s.albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  return s;
}
#endif
