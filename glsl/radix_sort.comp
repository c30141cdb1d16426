#version 450 core
// One 4-bit digit of a stable least-significant-digit radix sort of (key, value) pairs
// (render/gl/radix_sort.cpp), in two dispatches around a prefix sum of the blocks' digit counts:
//   LGH_RADIX_LOCAL:   each work group sorts its block of 1024 pairs by the digit in shared memory (four
//                      stable one-bit splits), writes the block sorted to the scratch pair and its 16 digit
//                      counts, digit-major (counts[digit * blocks + block]), so that their exclusive prefix
//                      sum is where each block's run of each digit goes;
//   LGH_RADIX_SCATTER: each pair of a sorted block goes to its run's offset plus its place in the run.
// Stable at every step (a split keeps order within each side; runs keep the blocks' order), so each pass
// keeps the order of the previous digits and the whole is std::stable_sort by key. No atomics decide an
// order: the result is the same on every run and every GPU.
layout(local_size_x = 256) in;
#include "shared/bindings.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer KeysIn { uint keysIn[]; };
layout(std430, binding = LGH_BINDING_PASS1) readonly buffer ValuesIn { uint valuesIn[]; };
layout(std430, binding = LGH_BINDING_PASS2) writeonly buffer KeysOut { uint keysOut[]; };
layout(std430, binding = LGH_BINDING_PASS3) writeonly buffer ValuesOut { uint valuesOut[]; };
// LOCAL: written, the blocks' digit counts; SCATTER: read, their exclusive prefix sum with the total last.
layout(std430, binding = LGH_BINDING_PASS4) buffer DigitCounts { uint digitCounts[]; };
uniform uint count;   // pairs
uniform uint blocks;  // ceil(count / 1024)
uniform uint shift;   // the digit's lowest bit

const uint kItemsPerThread = 4u;
const uint kBlockSize = 256u * kItemsPerThread;
const uint kDigits = 16u;

uint blockIndex() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }
uint digitOf(uint key) { return (key >> shift) & (kDigits - 1u); }

#ifdef LGH_RADIX_LOCAL
shared uint sharedKeys[2][kBlockSize];
shared uint sharedValues[2][kBlockSize];
shared uint partial[256];
shared uint digitTotals[kDigits];

void main() {
  uint block = blockIndex();
  if (block >= blocks) return;  // padding groups of a 2-D dispatch
  uint t = gl_LocalInvocationID.x, first = t * kItemsPerThread, base = block * kBlockSize;
  uint real = min(count - base, kBlockSize);  // the block's pairs; the padding after them sorts last
  for (uint i = 0u; i < kItemsPerThread; ++i) {
    uint local = first + i;
    sharedKeys[0][local] = local < real ? keysIn[base + local] : 0xffffffffu;
    sharedValues[0][local] = local < real ? valuesIn[base + local] : 0u;
  }
  if (t < kDigits) digitTotals[t] = 0u;
  barrier();
  // Four stable splits, lowest bit of the digit first: the pairs whose bit is 0 keep their order and go
  // first, the others follow in order. A thread owns 4 consecutive slots, so a scan of the threads'
  // counts of zeros places them.
  uint from = 0u;
  for (uint bit = 0u; bit < 4u; ++bit) {
    uint zeros = 0u;
    for (uint i = 0u; i < kItemsPerThread; ++i) zeros += 1u - ((sharedKeys[from][first + i] >> (shift + bit)) & 1u);
    partial[t] = zeros;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1u) {  // Hillis-Steele inclusive scan
      uint add = t >= offset ? partial[t - offset] : 0u;
      barrier();
      partial[t] += add;
      barrier();
    }
    uint allZeros = partial[255], zerosBefore = partial[t] - zeros;
    for (uint i = 0u; i < kItemsPerThread; ++i) {
      uint local = first + i, key = sharedKeys[from][local];
      bool one = ((key >> (shift + bit)) & 1u) != 0u;
      uint to = one ? allZeros + (local - zerosBefore) : zerosBefore;
      if (!one) ++zerosBefore;
      sharedKeys[1u - from][to] = key;
      sharedValues[1u - from][to] = sharedValues[from][local];
    }
    from = 1u - from;
    barrier();
  }
  for (uint i = 0u; i < kItemsPerThread; ++i) {
    uint local = first + i;
    keysOut[base + local] = sharedKeys[from][local];
    valuesOut[base + local] = sharedValues[from][local];
    if (local < real) atomicAdd(digitTotals[digitOf(sharedKeys[from][local])], 1u);  // a count: order-free
  }
  barrier();
  if (t < kDigits) digitCounts[t * blocks + block] = digitTotals[t];
}
#endif

#ifdef LGH_RADIX_SCATTER
shared uint runStart[kDigits];  // where each digit's run begins in the sorted block

void main() {
  uint block = blockIndex();
  if (block >= blocks) return;
  uint t = gl_LocalInvocationID.x, base = block * kBlockSize;
  uint real = min(count - base, kBlockSize);
  if (t == 0u) {
    uint start = 0u;
    for (uint d = 0u; d < kDigits; ++d) {
      runStart[d] = start;
      uint at = d * blocks + block;
      start += digitCounts[at + 1u] - digitCounts[at];  // the scan's last entry is the total
    }
  }
  barrier();
  for (uint i = 0u; i < kItemsPerThread; ++i) {
    uint local = t * kItemsPerThread + i;
    if (local >= real) break;
    uint key = keysIn[base + local], digit = digitOf(key);
    uint to = digitCounts[digit * blocks + block] + (local - runStart[digit]);
    keysOut[to] = key;
    valuesOut[to] = valuesIn[base + local];
  }
}
#endif
