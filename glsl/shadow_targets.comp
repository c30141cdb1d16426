#version 450 core
// Shadow-ray targets (docs/design.md §5): for every grid light of one level, `races` input lights, each
// drawn with probability equal to its share of the grid light's importance (lgh/cluster_shares.h),
// new every frame.
//
// Each draw is a race of exponential clocks (Efraimidis & Spirakis 2006): every source s of grid
// light V draws t = -ln(u) / (w a) and the smallest t wins, which is source s with probability
// w a / sum(w a). The sources of S1 (and of every level of a scatter build) are the input lights;
// those of a gathered level are the grid lights of the level below, and the winner hands on the
// input light its own race j drew. Race j at level l thus reaches input light i with the product of
// the shares along the way: i's share of V. Two kernels per level, both visiting every source and
// the corners of its cell at the level:
//   SHADOW_TARGETS_RACE  atomicMin of t's bits per (grid light, race)
//   (default)            the source whose t is that minimum writes its input light
// Both hash the same u from (source, corner, race, level, frame). Equal t from two sources (float
// ties, practically never) go to the smaller input light index: the result is deterministic.
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"
#include "shared/sampling.glsl"

#ifdef SHADOW_TARGETS_FROM_GRID_LIGHTS
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Sources { GpuGridLight sources[]; };
#else
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Sources { GpuLight sources[]; };
#endif
layout(std430, binding = LGH_BINDING_PASS1) readonly buffer TableKeys { uint tableKeys[]; };
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer SlotIndex { uint slotIndex[]; };
layout(std430, binding = LGH_BINDING_PASS4) buffer RaceTimes { uint raceTimes[]; };
layout(std430, binding = LGH_BINDING_PASS5) buffer Targets { uint targets[]; };
LGH_DEFINE_HASH_FIND(table, tableKeys, tableMask())

uniform uint sourceCount;
uniform uint sourceBase;   // index of the first source in the bound buffer
uniform uint sourceIndex;  // global index of that source: input light, or merged grid light
uniform uint levelOffset;  // merged index of the level's first grid light
uniform uint races;        // m
uniform uint seed;         // frame and level

void main() {
  uint i = lghGlobalIndex();
  if (i >= sourceCount) return;
  vec3 position = sources[sourceBase + i].position;
  float a = luminance(sources[sourceBase + i].intensity);
  if (!(a > 0.0)) return;
  uint source = sourceIndex + i;
  GridCell c = locateCell(position);
  for (uint corner = 0u; corner < 8u; ++corner) {
    uvec3 offset = cornerOffset(corner);
    precise float wa = cornerWeight(c.t, offset) * a;  // precise: both kernels must get the same bits
    if (!(wa > 0.0)) continue;
    uint slot = tableFind(vertexKey(c.cell + offset));
    if (slot == kEmptyKey) continue;  // cannot happen: the level was built from these sources
    uint parent = levelOffset + slotIndex[slot];
    Rng rng = makeRng(source * 8u + corner, seed);
    for (uint j = 0u; j < races; ++j) {
      precise float time = abs(log(1.0 - nextFloat(rng))) / wa;  // >= +0, so bits order as floats
      uint t = floatBitsToUint(time);
#ifdef SHADOW_TARGETS_RACE
      atomicMin(raceTimes[parent * races + j], t);
#else
      if (raceTimes[parent * races + j] != t) continue;
#ifdef SHADOW_TARGETS_FROM_GRID_LIGHTS
      uint light = targets[source * races + j];
#else
      uint light = source;
#endif
      atomicMin(targets[parent * races + j], light);
#endif
    }
  }
}
