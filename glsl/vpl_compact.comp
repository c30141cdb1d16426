#version 450 core
// Stable stream compaction of the VPL paths' slots (vpl_generate.comp) into S0, so that S0's order
// depends only on the paths, not on the order threads ran in:
//   LGH_COMPACT_FLAGS: slotIndex[s] = 1 for a written slot (flags != 0), else 0  (then an exclusive prefix sum)
//   LGH_COMPACT_WRITE: outputLights[outputOffset + slotIndex[s]] = slots[s] for every written slot
layout(local_size_x = 256) in;
#include "shared/bindings.h"
#include "shared/dispatch.glsl"
#include "shared/lgh_types.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Slots { GpuLight slots[]; };
layout(std430, binding = LGH_BINDING_PASS1) writeonly buffer Output { GpuLight outputLights[]; };
layout(std430, binding = LGH_BINDING_PASS2) buffer SlotIndex { uint slotIndex[]; };
uniform uint slotCount;
uniform uint outputOffset;

void main() {
  uint slot = lghGlobalIndex();
  if (slot >= slotCount) return;
  bool written = slots[slot].flags != 0u;
#ifdef LGH_COMPACT_FLAGS
  slotIndex[slot] = written ? 1u : 0u;
#else
  if (written) outputLights[outputOffset + slotIndex[slot]] = slots[slot];
#endif
}
