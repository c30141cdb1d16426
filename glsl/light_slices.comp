#version 450 core
// Sorts the culled light volumes by depth slice (shared/light_levels.h, sliceOf) so that the light
// pass draws each slice with its own stencil reference: a counting sort in three steps (`step`),
//   0  per light: its slice (from its sphere's nearest culling depth) and its rank within the slice
//   1  one invocation: slice offsets (prefix sum) and one indirect draw command per slice
//   2  per light: its index at offset[slice] + rank
// Order within a slice follows the atomics, not the light index.
layout(local_size_x = 64) in;
#include "shared/dispatch.glsl"
#include "shared/frame.glsl"
#include "shared/light_levels.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer GridLights { GpuGridLight lights[]; };
layout(std430, binding = LGH_BINDING_PASS1) coherent buffer SliceCounts { uint sliceCounts[]; };
layout(std430, binding = LGH_BINDING_PASS2) buffer SliceAndRank { uint sliceAndRank[]; };  // slice << 24 | rank
layout(std430, binding = LGH_BINDING_PASS3) writeonly buffer Commands { uint commands[]; };  // DrawArraysIndirectCommand
layout(std430, binding = LGH_BINDING_PASS4) writeonly buffer Sorted { uint sortedLights[]; };

uniform int step;
uniform uint first;     // index of the first light sorted in `lights`
uniform uint count;     // lights sorted
uniform uint slices;
uniform uint verticesPerVolume;
uniform float alpha, topCellSize, depthScale, margin;
uniform uint levels;

void main() {
  uint i = lghGlobalIndex();
  if (step == 1) {
    if (i != 0u) return;
    uint offset = 0u;
    for (uint k = 0u; k < slices; ++k) {
      commands[4u * k + 0u] = verticesPerVolume;
      commands[4u * k + 1u] = sliceCounts[k];
      commands[4u * k + 2u] = 0u;
      commands[4u * k + 3u] = offset;  // baseInstance: where the slice's lights start in sortedLights
      uint n = sliceCounts[k];
      sliceCounts[k] = offset;
      offset += n;
    }
    return;
  }
  if (i >= count) return;
  if (step == 0) {
    GpuGridLight l = lights[first + i];
    float r = 2.0 * levelRadius(alpha, topCellSize, l.level, levels) * (1.0 + margin);
    vec2 wRange = sphereClipWRange(frame.viewProjection, l.position, r);
    uint slice = sliceOf(cullingDepth(wRange.x * (1.0 - margin), depthScale), slices);
    sliceAndRank[i] = (slice << 24u) | atomicAdd(sliceCounts[slice], 1u);
  } else {
    uint slot = sliceAndRank[i];
    sortedLights[sliceCounts[slot >> 24u] + (slot & 0xffffffu)] = first + i;
  }
}
