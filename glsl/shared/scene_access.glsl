// Surface properties at a ray hit for compute shaders: geometric normal, texture coordinates and
// albedo (material factor x base colour texture, nearest texel with repeat wrap: VPL paths need the
// reflected colour, not a filtered image).
#ifndef LGH_SCENE_ACCESS_GLSL
#define LGH_SCENE_ACCESS_GLSL
#include "shared/bindings.h"
#include "shared/bvh_traverse.glsl"
#include "shared/scene_types.h"

layout(std430, binding = LGH_BINDING_SCENE_TRIANGLES) readonly buffer SceneTriangles { GpuSceneTriangle sceneTriangles[]; };
layout(std430, binding = LGH_BINDING_MATERIALS) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = LGH_BINDING_TEXTURE_INFOS) readonly buffer TextureInfos { GpuTextureInfo textureInfos[]; };
layout(std430, binding = LGH_BINDING_TEXELS) readonly buffer Texels { uint texels[]; };

vec3 srgbToLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

vec4 fetchTexture(int texture, vec2 uv) {
  if (texture < 0) return vec4(1.0);
  GpuTextureInfo info = textureInfos[texture];
  vec2 wrapped = uv - floor(uv);
  uint x = min(uint(wrapped.x * float(info.width)), info.width - 1u);
  uint y = min(uint(wrapped.y * float(info.height)), info.height - 1u);
  vec4 texel = unpackUnorm4x8(texels[info.firstTexel + y * info.width + x]);
  return vec4(srgbToLinear(texel.rgb), texel.a);
}

struct HitSurface {
  vec3 position;
  vec3 normal;   // geometric, unit, facing the incoming ray
  vec3 albedo;
  vec3 emission;
};

HitSurface hitSurface(vec3 origin, vec3 direction, RayHit hit) {
  HitSurface s;
  s.position = origin + hit.t * direction;
  GpuSceneTriangle tri = sceneTriangles[hit.sceneTriangle];
  vec2 uv = (1.0 - hit.barycentrics.x - hit.barycentrics.y) * tri.uv0 + hit.barycentrics.x * tri.uv1 +
            hit.barycentrics.y * tri.uv2;
  GpuMaterial m = materials[tri.material];
  s.albedo = clamp(m.baseColorFactor.rgb * fetchTexture(m.baseColorTexture, uv).rgb, 0.0, 1.0);
  s.emission = m.emission * fetchTexture(m.emissiveTexture, uv).rgb;
  BvhTriangle b = bvhTriangles[hit.bvhTriangle];
  vec3 n = cross(b.edge1, b.edge2);
  float len = length(n);
  s.normal = len > 0.0 ? n / len : -direction;
  if (dot(s.normal, direction) > 0.0) s.normal = -s.normal;
  return s;
}
#endif
