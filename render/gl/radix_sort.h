#pragma once
// Stable radix sort of (key, value) pairs of uints on the GPU, any length: least significant digit first,
// 4 bits per pass, each pass a block-local sort in shared memory, an exclusive prefix sum of the blocks'
// digit counts (PrefixSum) and a scatter (glsl/radix_sort.comp). Equal keys keep their order, so the
// result is std::stable_sort by key, the same on every run. Used by the light tree (Morton codes of S0).

#include <cstddef>
#include <string>

#include "render/gl/buffer.h"
#include "render/gl/prefix_sum.h"
#include "render/gl/program.h"

namespace lgh::gl {

class RadixSort {
 public:
  // owner: whose memory the scratch buffers are (gl/memory.h).
  explicit RadixSort(const std::string& owner);
  // Sorts keys[0, count) ascending, moving values[0, count) with them; only the low keyBits bits of the
  // keys are compared (higher bits must be 0 or equal), ceil(keyBits / 4) passes.
  void sort(const Buffer& keys, const Buffer& values, size_t count, int keyBits = 32);
  // Frees the scratch buffers (the next sort allocates them again).
  void release();

 private:
  std::string owner_;
  Program local_, scatter_;
  PrefixSum prefixSum_;
  Buffer scratchKeys_, scratchValues_;  // the blocks sorted locally
  Buffer otherKeys_, otherValues_;      // the other side of the passes' ping-pong
  Buffer digitCounts_;
};

}  // namespace lgh::gl
