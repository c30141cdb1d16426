#version 450 core
// Refits a finished level's vertex lookup to its occupied vertices. A level's table is sized before its
// keys are known (S1's from the input lights, a gathered level's from 8x the level below), which at scale
// leaves it mostly empty; the hierarchy keeps the lookup after the build (the shadow targets find grid
// lights through it), so its keys go into a table of about twice their count:
//   LGH_FIT_INSERT: ordered insertion of the level's keys (the same table for the same keys, any order)
//   otherwise:      each grid light writes its index at its key's slot
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer CompactKeys { uint compactKeys[]; };
layout(std430, binding = LGH_BINDING_PASS1) buffer TableKeys { uint tableKeys[]; };
layout(std430, binding = LGH_BINDING_PASS2) writeonly buffer SlotIndex { uint slotIndex[]; };
layout(std430, binding = LGH_BINDING_PASS3) buffer Counters { uint counters[]; };  // [0] unique keys, [1] overflow
LGH_DEFINE_HASH_TABLE(table, tableKeys, counters, tableMask())
uniform uint keyCount;

void main() {
  uint i = lghGlobalIndex();
  if (i >= keyCount) return;
#ifdef LGH_FIT_INSERT
  tableInsert(compactKeys[i]);
#else
  slotIndex[tableFind(compactKeys[i])] = i;
#endif
}
