#include "render/gl/uniform_blocks.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace lgh::gl {

UniformBlocks::UniformBlocks(std::string owner, size_t blockBytes) : owner_(std::move(owner)), blockBytes_(blockBytes) {
  GLint alignment = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const size_t a = size_t(std::max(alignment, 1));
  stride_ = (blockBytes + a - 1) / a * a;
}

void UniformBlocks::uploadBytes(const void* blocks, size_t blockBytes, size_t count) {
  if (blockBytes != blockBytes_) throw std::logic_error("UniformBlocks: a block of another size");
  const size_t bytes = std::max<size_t>(count, 1) * stride_;
  ensureSize(buffer_, {owner_, "uniform blocks"}, bytes);
  staging_.assign(bytes, 0);
  for (size_t i = 0; i < count; ++i)
    std::memcpy(staging_.data() + i * stride_, static_cast<const unsigned char*>(blocks) + i * blockBytes, blockBytes);
  buffer_.update(staging_.data(), staging_.size());
  count_ = count;
}

void UniformBlocks::bind(size_t index, GLuint binding) const {
  if (index >= count_) throw std::out_of_range("UniformBlocks: no such block uploaded");
  buffer_.bindRange(GL_UNIFORM_BUFFER, binding, index * stride_, blockBytes_);
}

}  // namespace lgh::gl
