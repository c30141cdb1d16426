#version 450 core
// Stream compaction of a level's hash table into a dense list of vertex keys:
//   LGH_COMPACT_FLAGS: slotIndex[s] = 1 for occupied slots, else 0   (then an exclusive prefix sum)
//   LGH_COMPACT_WRITE: compactKeys[slotIndex[s]] = key of occupied slot s
// After both, slotIndex[s] is the grid light index of the key in slot s.
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_types.h"
#include "shared/bindings.h"

layout(std430, binding = LGH_BINDING_PASS1) readonly buffer TableKeys { uint tableKeys[]; };
layout(std430, binding = LGH_BINDING_PASS2) buffer SlotIndex { uint slotIndex[]; };
layout(std430, binding = LGH_BINDING_PASS7) writeonly buffer CompactKeys { uint compactKeys[]; };
uniform uint capacity;

void main() {
  uint slot = lghGlobalIndex();
  if (slot >= capacity) return;
  uint key = tableKeys[slot];
#ifdef LGH_COMPACT_FLAGS
  slotIndex[slot] = key != kEmptyKey ? 1u : 0u;
#else
  if (key != kEmptyKey) compactKeys[slotIndex[slot]] = key;
#endif
}
