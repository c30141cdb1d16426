// Scene data as shaders read it: materials, punctual lights, per-frame camera uniforms.
#ifndef LGH_SCENE_TYPES_H
#define LGH_SCENE_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_STRUCT(GpuMaterial) {
  vec4 baseColorFactor;    // linear RGBA
  vec3 emission;           // emissiveFactor * emissive strength
  int baseColorTexture;    // index into the scene's textures, -1 if none
  int emissiveTexture;     // -1 if none
  float alphaCutoff;       // alphaMode MASK: alpha below this is cut out; < 0: opaque
  uint baseColorTexCoord;  // TEXCOORD set (0 or 1) each texture reads
  uint emissiveTexCoord;
  vec4 baseColorUvRow0;  // KHR_texture_transform as two rows: uv' = (dot(row0.xyz, (u, v, 1)), dot(row1.xyz, ...))
  vec4 baseColorUvRow1;
  vec4 emissiveUvRow0;
  vec4 emissiveUvRow1;
};
GPU_CHECK_SIZE(GpuMaterial, 112);
GPU_CHECK_OFFSET(GpuMaterial, baseColorUvRow0, 48);

GPU_CONST uint kLightPoint = 0u;
GPU_CONST uint kLightSpot = 1u;
GPU_CONST uint kLightDirectional = 2u;

GPU_STRUCT(GpuPunctualLight) {
  vec3 position;
  uint type;       // kLightPoint, kLightSpot, kLightDirectional
  vec3 direction;  // unit direction the light travels (spot, directional)
  float range;     // 0 = infinite
  vec3 intensity;  // W/sr (point, spot) or W/m^2 (directional), RGB
  float innerConeCos;
  float outerConeCos;
  uint pad0, pad1, pad2;
};
GPU_CHECK_SIZE(GpuPunctualLight, 64);

// What a compute shader needs at a ray hit besides the BVH: the material and the corners' vertices.
GPU_STRUCT(GpuSceneTriangle) {
  uint material;
  uint vertex0, vertex1, vertex2;  // indices into the scene vertices
};
GPU_CHECK_SIZE(GpuSceneTriangle, 16);

// Vertex attributes that materials read (the rasterizer gets the same values as vertex streams).
GPU_STRUCT(GpuSceneVertex) {
  vec4 texcoords;  // xy: TEXCOORD_0, zw: TEXCOORD_1
  vec4 color;      // COLOR_0, linear RGBA (white where the file has none)
};
GPU_CHECK_SIZE(GpuSceneVertex, 32);

// A texture in the packed texel buffer (RGBA8 per uint, rows top-down, sRGB-encoded).
GPU_STRUCT(GpuTextureInfo) {
  uint firstTexel;
  uint width;
  uint height;
  uint pad;
};
GPU_CHECK_SIZE(GpuTextureInfo, 16);

// A source of light paths for VPL generation, chosen with probability proportional to its power.
GPU_CONST uint kEmitterPunctual = 0u;  // `light` indexes the punctual lights
GPU_CONST uint kEmitterTriangle = 1u;  // an emissive triangle: v0, edge1, edge2, radiance
GPU_STRUCT(GpuEmitter) {
  vec3 v0;
  uint kind;  // kEmitterPunctual or kEmitterTriangle
  vec3 edge1;
  float cdf;  // inclusive cumulative selection probability
  vec3 edge2;
  float selectionPdf;  // probability of choosing this emitter
  vec3 radiance;       // triangle: emitted radiance (emissive factor x strength); punctual: unused
  uint light;          // punctual: index into the punctual lights; triangle: scene triangle index
};
GPU_CHECK_SIZE(GpuEmitter, 64);

// Per-frame uniforms (std140; the layout rules in gpu_prelude.h make std140 and C++ agree here).
GPU_STRUCT(FrameUniforms) {
  mat4 viewProjection;
  mat4 inverseViewProjection;
  mat4 cameraRelativeViewProjection;  // projection x view rotation: clip = M (p - cameraPosition), see camera_view.h
  vec4 cameraPosition;                // xyz; w unused
  uvec4 resolution;                   // width, height, frame index, 0
  vec4 sceneScale;                    // x: scene bounds diagonal, y: clamp distance d_c, z: pixel footprint per unit
                                      // distance from the camera (2 tan(fovy/2) / height), w: clip w of the near
                                      // plane (no surface is nearer; the light pass's volumeDepth)
};
GPU_CHECK_SIZE(FrameUniforms, 240);

GPU_NAMESPACE_END
#endif
