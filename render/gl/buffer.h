#pragma once
// A GL buffer with immutable storage. Typed upload/download keep element counts in one place; the
// label says who holds it, and its bytes are in gl::memory() while it lives.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "render/gl/memory.h"
#include "render/gl/resource.h"

namespace lgh::gl {

class Buffer {
 public:
  Buffer() = default;
  // flags: GL_DYNAMIC_STORAGE_BIT to allow update(); storage is zero-initialised when data is null.
  // Throws gl::OutOfMemory when the bytes exceed the memory budget (gl/memory.h).
  Buffer(Label label, size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  template <typename T>
  static Buffer fromVector(Label label, const std::vector<T>& v, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
    return Buffer(std::move(label), v.size() * sizeof(T), v.empty() ? nullptr : v.data(), flags);
  }

  GLuint id() const { return handle_.id(); }
  size_t size() const { return bytes_; }
  const Label& label() const { return label_; }
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

  // target: GL_SHADER_STORAGE_BUFFER, GL_UNIFORM_BUFFER, GL_ATOMIC_COUNTER_BUFFER. A storage binding
  // longer than one storage block may span (GL_MAX_SHADER_STORAGE_BLOCK_SIZE) throws gl::OutOfMemory
  // naming the buffer: GL would bind it without complaint and the shader read past the block's end.
  void bindBase(GLenum target, GLuint index) const;
  void bindRange(GLenum target, GLuint index, size_t offset, size_t bytes) const;

 private:
  void checkStorageBlock(GLenum target, size_t bytes) const;

  Label label_;
  Allocation allocation_;
  Handle<DeleteBuffer> handle_;
  size_t bytes_ = 0;
};

// Grows (reallocates, contents lost) a buffer to at least `bytes`; returns true if it was reallocated.
bool ensureSize(Buffer& buffer, const Label& label, size_t bytes, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
// Reallocates (contents lost) a buffer unless it holds exactly `bytes`: for what a configuration sizes
// (pixels, lights), so that a smaller configuration holds less again. Returns true if it was reallocated.
bool fitSize(Buffer& buffer, const Label& label, size_t bytes, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);

// GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes one shader storage block may span (128 MiB on llvmpipe).
size_t maxStorageBlockBytes();

// The least GL_MAX_SHADER_STORAGE_BLOCK_SIZE of any GL 4.3+ implementation (16 MiB).
inline constexpr size_t kMinStorageBlockBytes = size_t(1) << 24;

// The most elements of `elementSize` bytes one storage block binding holds (at least
// kMinStorageBlockBytes' worth), a multiple of the elements per GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT
// so that chunks bound one after another all start aligned.
size_t storageBlockElements(size_t elementSize);

}  // namespace lgh::gl
