#pragma once
// Exclusive prefix sum of a uint buffer on the GPU, any length: scan 1024-value blocks, scan the
// block totals recursively, add them back. Used for stream compaction (flags -> output indices).

#include <vector>

#include "render/gl/buffer.h"
#include "render/gl/program.h"

namespace lgh::gl {

class PrefixSum {
 public:
  PrefixSum();
  // Replaces values[0, count) by their exclusive prefix sum and returns the total.
  GLuint scan(const Buffer& values, size_t count);

 private:
  GLuint scanLevel(const Buffer& values, size_t count, size_t depth);
  Program scanBlocks_, addBlocks_;
  std::vector<Buffer> blockSums_;  // one per recursion depth, reused across calls
};

}  // namespace lgh::gl
