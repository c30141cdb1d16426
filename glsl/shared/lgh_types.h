// The lighting grid hierarchy as the GPU holds it: input lights S0, grid lights of all levels, and
// the per-level table the light pass reads. Written by render/passes/lgh_build_pass.cpp.
#ifndef LGH_LGH_TYPES_H
#define LGH_LGH_TYPES_H
#include "shared/gpu_prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST uint kLightOriented = 1u;  // GpuLight::flags: a cosine emitter with normal `normalOct`

// The GPU build keys grid vertices by 32-bit linear indices: (2^(L-1)+1)^3 < 2^32 allows L <= 11
// (an S1 cell of H/1024).
GPU_CONST uint kMaxBuildLevels = 11u;

// An input light (S0): a VPL, an emitter sample or a glTF point light. 32 bytes, so 4M lights fit one
// 128 MiB shader storage block.
GPU_STRUCT(GpuLight) {
  vec3 position;
  uint normalOct;  // octahedral unit normal, snorm16 x 2 (see shared/octahedral.h); ignored for omni lights
  vec3 intensity;  // RGB, W/sr (peak intensity I = Phi/pi for a cosine emitter)
  uint flags;      // kLightOriented
};
GPU_CHECK_SIZE(GpuLight, 32);
// Two 16-byte texels, a vec3 and a word each (the shadow-ray pass reads them as texels).
GPU_CHECK_OFFSET(GpuLight, normalOct, 12);
GPU_CHECK_OFFSET(GpuLight, intensity, 16);
GPU_CHECK_OFFSET(GpuLight, flags, 28);

// A grid light of level >= 1 (or an S0 light rendered at level 0). 64 bytes.
GPU_STRUCT(GpuGridLight) {
  vec3 position;       // illumination centre
  uint level;          // 0 for S0, 1..L for grid levels
  vec3 intensity;      // summed RGB intensity (energy kept)
  float omniFraction;  // share of omni emission O/W
  vec3 variance;       // per-axis variance of the centre, >= 0
  uint vertexKey;      // linear index of its vertex at its level (x + n(y + n z), n = vertices per axis)
  vec3 meanNormal;     // N/W, |m| <= 1
  uint pad;
};
GPU_CHECK_SIZE(GpuGridLight, 64);
GPU_CHECK_OFFSET(GpuGridLight, meanNormal, 48);

// The bounds reduction's result (lgh_bounds.comp): bounds of the lit lights and of all lights (the
// fallback when none is lit), the largest of lum(I) and I's channels (sets the S1 scatter's fixed-point
// scale) and the number of lit lights. Floats are stored as orderedBits() so that uint atomicMin and
// atomicMax order them as floats.
GPU_STRUCT(LghBoundsResult) {
  uint litLower[4];  // [0..2] used
  uint litUpper[4];
  uint allLower[4];
  uint allUpper[4];
  uint largestValue;
  uint litCount;
  uint pad0, pad1;
};
GPU_CHECK_SIZE(LghBoundsResult, 80);

// A float's bits mapped so that unsigned order is float order (negatives reversed below positives).
GPU_FUNC uint orderedBits(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}
GPU_FUNC float fromOrderedBits(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? (u & 0x7fffffffu) : ~u); }

// Grid geometry and the fixed-point scale of one build (uniform block for the build kernels).
GPU_STRUCT(LghGridParams) {
  vec4 originAndTopCell;  // xyz: min corner of the top cell, w: H
  uvec4 levelsAndCounts;  // x: L, y: level being built, z: light count, w: vertices per axis at that level
  vec4 cellSizeAndScale;  // x: h of the level being built, y: fixed-point scale, zw: unused
  uvec4 table;            // x: hash capacity (power of two), y: capacity - 1, z: unique-key stop count, w: unused
};
GPU_CHECK_SIZE(LghGridParams, 64);

GPU_CONST uint kEmptyKey = 0xffffffffu;

GPU_NAMESPACE_END
#endif
