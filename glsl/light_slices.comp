#version 450 core
// Sorts the culled light volumes by depth slice (shared/light_levels.h, sliceOf) so that the light
// pass draws each slice with its own stencil reference: a stable counting sort in three steps (`step`),
//   0  one work group, over lights [rangeStart, rangeStart + rangeCount): each light's slice (from its
//      sphere's nearest culling depth) and its rank among the earlier lights of that slice, in light
//      order; the running counts per slice carry over between dispatches in sliceCounts
//   1  one invocation: slice offsets (prefix sum) and one indirect draw command per slice
//   2  per light: its index at offset[slice] + rank
// Spheres that reach the eye plane (no finite screen bound) go to one more bucket after the slices,
// `slices`: they are drawn as icosahedra (kCrossingVolumeVertices vertices; their index flagged
// kCrossingVolume), not as octagons.
// Stable, so the draw order, and with it the blending sums and the shadow selection, is the same on
// every run. Step 0 runs in ranges so that no invocation loops past llvmpipe's 65,535 iterations.
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
uniform uint rangeStart, rangeCount;  // step 0: this dispatch's lights (relative to `first`)
uniform uint slices;
uniform uint verticesPerVolume;  // of an octagon; crossing spheres: kCrossingVolumeVertices
uniform float alpha, topCellSize, depthScale, margin;
uniform uint levels;

const uint kNoSlice = 0xffffffffu;
shared uint chunkSlices[64];
shared uint runningCounts[kMaxCullingSlices + 1u];

// The light's slice, or `slices` for a sphere that reaches the eye plane (light_volume.vert's
// culledCorner would give it the whole viewport). One wholly behind the eye stays an octagon (slice 0),
// which culledCorner draws as nothing.
uint sliceOfLight(uint i) {
  GpuGridLight l = lights[first + i];
  float r = 2.0 * levelRadius(alpha, topCellSize, l.level, levels) * (1.0 + margin);
  vec2 wRange = sphereClipWRange(frame.viewProjection, l.position, r);
  vec4 bounds, diagonals;
  if (wRange.y > 0.0 && !projectedSphereBounds(frame.viewProjection, l.position, r, bounds, diagonals))
    return slices;
  return sliceOf(cullingDepth(wRange.x * (1.0 - margin), depthScale), slices);
}

// Step 0: 64 lights at a time; a light's rank is the slice's running count plus the earlier lights of
// its slice in the chunk; then the chunk's last light of each slice advances the running count.
void rankInOrder() {
  uint t = gl_LocalInvocationID.x;
  for (uint k = t; k <= slices; k += 64u) runningCounts[k] = sliceCounts[k];
  barrier();
  for (uint base = rangeStart; base < rangeStart + rangeCount; base += 64u) {
    uint i = base + t;
    bool valid = i < rangeStart + rangeCount;
    uint slice = valid ? sliceOfLight(i) : kNoSlice;
    chunkSlices[t] = slice;
    barrier();
    uint before = 0u;
    bool lastOfSlice = valid;
    for (uint j = 0u; j < 64u; ++j) {
      if (j < t && chunkSlices[j] == slice) ++before;
      if (j > t && chunkSlices[j] == slice) lastOfSlice = false;
    }
    if (valid) sliceAndRank[i] = (slice << 24u) | (runningCounts[slice] + before);
    barrier();
    if (lastOfSlice) runningCounts[slice] += before + 1u;
    barrier();
  }
  for (uint k = t; k <= slices; k += 64u) sliceCounts[k] = runningCounts[k];
}

void main() {
  if (step == 0) {
    rankInOrder();
    return;
  }
  uint i = lghGlobalIndex();
  if (step == 1) {
    if (i != 0u) return;
    uint offset = 0u;
    for (uint k = 0u; k <= slices; ++k) {
      commands[4u * k + 0u] = k < slices ? verticesPerVolume : kCrossingVolumeVertices;
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
  uint slot = sliceAndRank[i];
  uint slice = slot >> 24u;
  sortedLights[sliceCounts[slice] + (slot & 0xffffffu)] = (first + i) | (slice == slices ? kCrossingVolume : 0u);
}
