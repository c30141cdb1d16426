// Material evaluation shared by the G-buffer (rasterized, filtered textures) and by compute shaders at
// ray hits (nearest texels): which TEXCOORD set a texture reads, its KHR_texture_transform, and the
// alpha test of alphaMode MASK. One definition, so the camera, the shadow rays and the VPL paths cut
// out exactly the same points.
#ifndef LGH_MATERIAL_EVAL_H
#define LGH_MATERIAL_EVAL_H
#include "shared/scene_types.h"

GPU_NAMESPACE_BEGIN

// `texcoords`: xy TEXCOORD_0, zw TEXCOORD_1 of the surface point.
GPU_FUNC vec2 baseColorUv(GpuMaterial m, vec4 texcoords) {
  vec2 uv = m.baseColorTexCoord == 1u ? vec2(texcoords.z, texcoords.w) : vec2(texcoords.x, texcoords.y);
  return vec2(dot(vec3(m.baseColorUvRow0), vec3(uv, 1.0f)), dot(vec3(m.baseColorUvRow1), vec3(uv, 1.0f)));
}

GPU_FUNC vec2 emissiveUv(GpuMaterial m, vec4 texcoords) {
  vec2 uv = m.emissiveTexCoord == 1u ? vec2(texcoords.z, texcoords.w) : vec2(texcoords.x, texcoords.y);
  return vec2(dot(vec3(m.emissiveUvRow0), vec3(uv, 1.0f)), dot(vec3(m.emissiveUvRow1), vec3(uv, 1.0f)));
}

// glTF: alpha = baseColorFactor.a x texture alpha x COLOR_0 alpha; MASK keeps alpha >= alphaCutoff.
GPU_FUNC bool alphaCutOut(GpuMaterial m, float textureAlpha, float vertexAlpha) {
  return m.alphaCutoff >= 0.0f && m.baseColorFactor.w * textureAlpha * vertexAlpha < m.alphaCutoff;
}

GPU_NAMESPACE_END
#endif
