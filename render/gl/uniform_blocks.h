#pragma once
// One uniform block (a GPU_STRUCT of glsl/shared) per draw or dispatch of a pass, all in one buffer at
// the offsets GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT allows: upload() them before the first, then bind(i)
// before the i-th. (One upload per pass, not one buffer update between dependent dispatches.)

#include <cstddef>
#include <string>
#include <vector>

#include "render/gl/buffer.h"

namespace lgh::gl {

class UniformBlocks {
 public:
  // owner: the pass whose memory the blocks are (gl/memory.h).
  UniformBlocks(std::string owner, size_t blockBytes);

  template <typename Block>
  void upload(const std::vector<Block>& blocks) {
    uploadBytes(blocks.data(), sizeof(Block), blocks.size());
  }
  void release() {
    buffer_ = {};
    count_ = 0;
  }
  // Binds block `index` of the last upload() to uniform binding point `binding`.
  void bind(size_t index, GLuint binding) const;

 private:
  void uploadBytes(const void* blocks, size_t blockBytes, size_t count);

  std::string owner_;
  size_t blockBytes_ = 0, stride_ = 0, count_ = 0;
  std::vector<unsigned char> staging_;
  Buffer buffer_;
};

}  // namespace lgh::gl
