// Scene materials for compute shaders: the triangle, vertex, material and packed-texel buffers, and
// the surface attributes at a point of a triangle (texture coordinates, vertex colour, albedo,
// emission, alpha). Textures are read as nearest texels with repeat wrap: VPL paths and shadow rays
// need the reflected colour and the cut-out, not a filtered image.
#ifndef LGH_SCENE_MATERIALS_GLSL
#define LGH_SCENE_MATERIALS_GLSL
#include "shared/bindings.h"
#include "shared/material_eval.h"
#include "shared/scene_types.h"

layout(std430, binding = LGH_BINDING_SCENE_TRIANGLES) readonly buffer SceneTriangles { GpuSceneTriangle sceneTriangles[]; };
layout(std430, binding = LGH_BINDING_SCENE_VERTICES) readonly buffer SceneVertices { GpuSceneVertex sceneVertices[]; };
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

struct SurfacePoint {
  GpuMaterial material;
  vec4 texcoords;  // xy: TEXCOORD_0, zw: TEXCOORD_1
  vec4 color;      // COLOR_0
};

// (u, v): barycentric weights of corners 1 and 2.
SurfacePoint surfacePoint(uint sceneTriangle, vec2 barycentrics) {
  GpuSceneTriangle tri = sceneTriangles[sceneTriangle];
  GpuSceneVertex a = sceneVertices[tri.vertex0], b = sceneVertices[tri.vertex1], c = sceneVertices[tri.vertex2];
  float w = 1.0 - barycentrics.x - barycentrics.y;
  SurfacePoint p;
  p.material = materials[tri.material];
  p.texcoords = w * a.texcoords + barycentrics.x * b.texcoords + barycentrics.y * c.texcoords;
  p.color = w * a.color + barycentrics.x * b.color + barycentrics.y * c.color;
  return p;
}

vec3 surfaceAlbedo(SurfacePoint p) {
  vec3 texel = fetchTexture(p.material.baseColorTexture, baseColorUv(p.material, p.texcoords)).rgb;
  return clamp(p.material.baseColorFactor.rgb * texel * p.color.rgb, 0.0, 1.0);
}

vec3 surfaceEmission(SurfacePoint p) {
  return p.material.emission * fetchTexture(p.material.emissiveTexture, emissiveUv(p.material, p.texcoords)).rgb;
}

// True where alphaMode MASK removes the surface (the point is not there for any ray).
bool surfaceCutOut(uint sceneTriangle, vec2 barycentrics) {
  SurfacePoint p = surfacePoint(sceneTriangle, barycentrics);
  float textureAlpha = fetchTexture(p.material.baseColorTexture, baseColorUv(p.material, p.texcoords)).a;
  return alphaCutOut(p.material, textureAlpha, p.color.a);
}
#endif
