#pragma once
// Exclusive prefix sum of a uint buffer on the GPU, any length: scan 1024-value blocks, scan the
// block totals recursively, add them back. Used for stream compaction (flags -> output indices).

#include <string>
#include <vector>

#include "render/gl/buffer.h"
#include "render/gl/program.h"

namespace lgh::gl {

class PrefixSum {
 public:
  // owner: whose memory the block sums are (gl/memory.h).
  explicit PrefixSum(std::string owner);
  // Replaces values[0, count) by their exclusive prefix sum and returns the total.
  GLuint scan(const Buffer& values, size_t count);
  void release() {
    for (Buffer& b : blockSums_) b = {};
  }

 private:
  GLuint scanLevel(const Buffer& values, size_t count, size_t depth);
  std::string owner_;
  Program scanBlocks_, addBlocks_;
  std::vector<Buffer> blockSums_;  // one per recursion depth, reused across calls
};

}  // namespace lgh::gl
