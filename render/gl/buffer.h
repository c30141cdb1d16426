#pragma once
// A GL buffer with immutable storage. Typed upload/download keep element counts in one place.

#include <cstddef>
#include <string>
#include <vector>

#include "render/gl/resource.h"

namespace lgh::gl {

class Buffer {
 public:
  Buffer() = default;
  // flags: GL_DYNAMIC_STORAGE_BIT to allow update(); storage is zero-initialised when data is null.
  explicit Buffer(size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  template <typename T>
  static Buffer fromVector(const std::vector<T>& v, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
    return Buffer(v.size() * sizeof(T), v.empty() ? nullptr : v.data(), flags);
  }

  GLuint id() const { return handle_.id(); }
  size_t size() const { return bytes_; }
  explicit operator bool() const { return bool(handle_); }

  void update(const void* data, size_t bytes, size_t offset = 0);
  template <typename T>
  void update(const std::vector<T>& v, size_t offsetElements = 0) {
    update(v.data(), v.size() * sizeof(T), offsetElements * sizeof(T));
  }
  void clear();  // fills with zero bytes
  void clearUint(GLuint value);

  void read(void* out, size_t bytes, size_t offset = 0) const;
  template <typename T>
  std::vector<T> download(size_t count, size_t offsetElements = 0) const {
    std::vector<T> out(count);
    if (count) read(out.data(), count * sizeof(T), offsetElements * sizeof(T));
    return out;
  }
  template <typename T>
  std::vector<T> downloadAll() const {
    return download<T>(bytes_ / sizeof(T));
  }

  // target: GL_SHADER_STORAGE_BUFFER, GL_UNIFORM_BUFFER, GL_ATOMIC_COUNTER_BUFFER.
  void bindBase(GLenum target, GLuint index) const;
  void bindRange(GLenum target, GLuint index, size_t offset, size_t bytes) const;

 private:
  Handle<DeleteBuffer> handle_;
  size_t bytes_ = 0;
};

// Grows (reallocates, contents lost) a buffer to at least `bytes`; returns true if it was reallocated.
bool ensureSize(Buffer& buffer, size_t bytes, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);

// GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes one shader storage block may span (128 MiB on llvmpipe).
size_t maxStorageBlockBytes();

// The least GL_MAX_SHADER_STORAGE_BLOCK_SIZE of any GL 4.3+ implementation (16 MiB).
inline constexpr size_t kMinStorageBlockBytes = size_t(1) << 24;

// The most elements of `elementSize` bytes one storage block binding holds (at least
// kMinStorageBlockBytes' worth), a multiple of the elements per GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT
// so that chunks bound one after another all start aligned.
size_t storageBlockElements(size_t elementSize);

}  // namespace lgh::gl
