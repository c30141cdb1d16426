#version 450 core
#ifdef LGH_FLOAT_ATOMICS
#extension GL_NV_shader_atomic_float : require
#endif
// Scatters input lights S0 into the vertices of one level (S1 in the paper's fast path, every level
// in the reference "scatter" build): each light adds its trilinearly weighted sums to the 8 corners
// of its cell, whose slots lgh_insert_keys registered and lgh_compact numbered.
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"
#include "shared/lgh_accumulators.glsl"
#include "shared/octahedral.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = LGH_BINDING_PASS1) readonly buffer TableKeys { uint tableKeys[]; };
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer SlotIndex { uint slotIndex[]; };
LGH_DEFINE_HASH_FIND(table, tableKeys, tableMask())
uniform uint lightCount;

void main() {
  uint i = lghGlobalIndex();
  if (i >= lightCount) return;
  GpuLight light = lights[i];
  float a = luminance(light.intensity);
  if (!(a > 0.0)) return;
  bool oriented = (light.flags & kLightOriented) != 0u;
  vec3 n = oriented ? octDecode(light.normalOct) : vec3(0.0);
  GridCell c = locateCell(light.position);
  for (uint corner = 0u; corner < 8u; ++corner) {
    uvec3 offset = cornerOffset(corner);
    float w = cornerWeight(c.t, offset);
    if (!(w > 0.0)) continue;
    uvec3 v = c.cell + offset;
    uint slot = tableFind(vertexKey(v));
    if (slot == kEmptyKey) continue;  // cannot happen after lgh_insert_keys; never write out of bounds
    uint index = slotIndex[slot];
    float wa = w * a;
    vec3 e = (light.position - vertexPosition(v)) / gridCellSize();  // offset in cells, |e| <= 1
    for (uint k = 0u; k < 3u; ++k) {
      accPositionAdd(6u * index + k, wa * e[k]);
      accPositionAdd(6u * index + 3u + k, wa * e[k] * e[k]);
      accIntensityAdd(3u * index + k, w * light.intensity[k]);
      if (oriented) accNormalAdd(4u * index + k, wa * n[k]);
    }
    if (!oriented) accNormalAdd(4u * index + 3u, wa);
  }
}
