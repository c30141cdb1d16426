#include "render/gl/prefix_sum.h"

#include <string>
#include <utility>

#include "shared/bindings.h"

namespace lgh::gl {
namespace {
constexpr size_t kBlockSize = 1024;  // 256 threads x 4 items, as in glsl/prefix_sum.comp
}

PrefixSum::PrefixSum(std::string owner)
    : owner_(std::move(owner)),
      scanBlocks_(Program::compute("prefix_sum.comp", {{"LGH_SCAN_BLOCKS", "1"}})),
      addBlocks_(Program::compute("prefix_sum.comp", {{"LGH_SCAN_ADD", "1"}})),
      // 1024^4 values is past any 32-bit count: four levels of block sums always suffice, and sizing
      // the vector once keeps references to its buffers valid through the recursion.
      blockSums_(4) {}

GLuint PrefixSum::scan(const Buffer& values, size_t count) {
  if (count == 0) return 0;
  return scanLevel(values, count, 0);
}

GLuint PrefixSum::scanLevel(const Buffer& values, size_t count, size_t depth) {
  const size_t blocks = (count + kBlockSize - 1) / kBlockSize;
  ensureSize(blockSums_[depth], {owner_, "prefix sum " + std::to_string(depth)}, (blocks + 1) * sizeof(GLuint));
  const Buffer& sums = blockSums_[depth];

  values.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  sums.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  scanBlocks_.set("count", GLuint(count));
  scanBlocks_.dispatch1D(blocks * 256, 256);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);

  GLuint total = 0;
  if (blocks == 1) {
    sums.read(&total, sizeof(GLuint));
    return total;
  }
  // Scan the block totals (recursively), then add each block's offset to its values.
  total = scanLevel(sums, blocks, depth + 1);
  values.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  sums.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  addBlocks_.set("count", GLuint(count));
  addBlocks_.dispatch1D(blocks * 256, 256);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  return total;
}

}  // namespace lgh::gl
