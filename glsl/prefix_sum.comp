#version 450 core
// Exclusive prefix sum of uints, one step of a multi-level scan (render/gl/prefix_sum.cpp):
//   LGH_SCAN_BLOCKS: each work group scans 1024 values in place and writes its total to blockSums;
//   LGH_SCAN_ADD:    adds the scanned block sums back to every value of their block.
// Values can be 0/1 flags; counting them this way is stream compaction without atomics.
layout(local_size_x = 256) in;
#include "shared/bindings.h"

layout(std430, binding = LGH_BINDING_PASS0) buffer Values { uint values[]; };
layout(std430, binding = LGH_BINDING_PASS1) buffer BlockSums { uint blockSums[]; };
uniform uint count;

const uint kItemsPerThread = 4u;
const uint kBlockSize = 256u * kItemsPerThread;
shared uint partial[256];

uint blockIndex() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }

void main() {
  uint block = blockIndex();
  if (block * kBlockSize >= count) return;  // padding groups of a 2-D dispatch
  uint base = block * kBlockSize + gl_LocalInvocationID.x * kItemsPerThread;
#ifdef LGH_SCAN_BLOCKS
  // Each thread scans its 4 items serially, then the 256 thread totals are scanned in shared memory.
  uint items[kItemsPerThread];
  uint sum = 0u;
  for (uint i = 0u; i < kItemsPerThread; ++i) {
    items[i] = base + i < count ? values[base + i] : 0u;
    sum += items[i];
  }
  partial[gl_LocalInvocationID.x] = sum;
  barrier();
  // Hillis-Steele inclusive scan over the thread totals.
  for (uint offset = 1u; offset < 256u; offset <<= 1u) {
    uint add = gl_LocalInvocationID.x >= offset ? partial[gl_LocalInvocationID.x - offset] : 0u;
    barrier();
    partial[gl_LocalInvocationID.x] += add;
    barrier();
  }
  uint running = partial[gl_LocalInvocationID.x] - sum;  // exclusive prefix of this thread
  for (uint i = 0u; i < kItemsPerThread; ++i) {
    if (base + i < count) values[base + i] = running;
    running += items[i];
  }
  if (gl_LocalInvocationID.x == 255u) blockSums[block] = partial[255];
#endif
#ifdef LGH_SCAN_ADD
  uint offset = blockSums[block];
  for (uint i = 0u; i < kItemsPerThread; ++i)
    if (base + i < count) values[base + i] += offset;
#endif
}
