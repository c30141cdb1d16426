// Scene data as shaders read it: materials, punctual lights, per-frame camera uniforms.
#ifndef LGH_SCENE_TYPES_H
#define LGH_SCENE_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_STRUCT(GpuMaterial) {
  vec4 baseColorFactor;   // linear RGBA
  vec3 emission;          // emissiveFactor * emissive strength
  int baseColorTexture;   // index into the scene's textures, -1 if none
  int emissiveTexture;    // -1 if none
  uint pad0, pad1, pad2;
};
GPU_CHECK_SIZE(GpuMaterial, 48);

GPU_CONST uint kLightPoint = 0u;
GPU_CONST uint kLightSpot = 1u;
GPU_CONST uint kLightDirectional = 2u;

GPU_STRUCT(GpuPunctualLight) {
  vec3 position;
  uint type;           // kLightPoint, kLightSpot, kLightDirectional
  vec3 direction;      // unit direction the light travels (spot, directional)
  float range;         // 0 = infinite
  vec3 intensity;      // W/sr (point, spot) or W/m^2 (directional), RGB
  float innerConeCos;
  float outerConeCos;
  uint pad0, pad1, pad2;
};
GPU_CHECK_SIZE(GpuPunctualLight, 64);

// What a compute shader needs at a ray hit besides the BVH: material and texture coordinates.
GPU_STRUCT(GpuSceneTriangle) {
  uint material;
  uint pad;
  vec2 uv0;
  vec2 uv1;
  vec2 uv2;
};
GPU_CHECK_SIZE(GpuSceneTriangle, 32);

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
  uint kind;           // kEmitterPunctual or kEmitterTriangle
  vec3 edge1;
  float cdf;           // inclusive cumulative selection probability
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
  vec4 cameraPosition;   // xyz; w unused
  uvec4 resolution;      // width, height, frame index, 0
  vec4 sceneScale;       // x: scene bounds diagonal, y: clamp distance d_c, z: pixel footprint per unit
                         // distance from the camera (2 tan(fovy/2) / height), w: unused
};
GPU_CHECK_SIZE(FrameUniforms, 176);

GPU_NAMESPACE_END
#endif
