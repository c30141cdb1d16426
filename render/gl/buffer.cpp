#include "render/gl/buffer.h"

#include <algorithm>
#include <stdexcept>

namespace lgh::gl {

Buffer::Buffer(size_t bytes, const void* data, GLbitfield flags) : bytes_(bytes) {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  handle_ = Handle<DeleteBuffer>(name);
  // Zero-sized storage is invalid in GL; keep a 16-byte stub so bindings stay legal.
  const size_t storage = bytes ? bytes : 16;
  glNamedBufferStorage(name, GLsizeiptr(storage), data, flags);
  if (!data) clear();
}

void Buffer::update(const void* data, size_t bytes, size_t offset) {
  if (offset + bytes > bytes_) throw std::out_of_range("Buffer::update past the end of the buffer");
  if (bytes) glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::clear() { clearUint(0); }

void Buffer::clearUint(GLuint value) {
  glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}

void Buffer::read(void* out, size_t bytes, size_t offset) const {
  if (offset + bytes > bytes_) throw std::out_of_range("Buffer::read past the end of the buffer");
  if (bytes) glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), out);
}

void Buffer::bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }

void Buffer::bindRange(GLenum target, GLuint index, size_t offset, size_t bytes) const {
  glBindBufferRange(target, index, id(), GLintptr(offset), GLsizeiptr(bytes ? bytes : 16));
}

bool ensureSize(Buffer& buffer, size_t bytes, GLbitfield flags) {
  if (buffer && buffer.size() >= bytes) return false;
  buffer = Buffer(bytes, nullptr, flags);
  return true;
}

size_t maxStorageBlockBytes() {
  GLint64 bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
  return size_t(std::max<GLint64>(bytes, 0));
}

size_t storageBlockElements(size_t elementSize) {
  GLint alignment = 256;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const size_t step = std::max<size_t>(1, size_t(alignment) / elementSize);
  return std::max(std::max(maxStorageBlockBytes(), kMinStorageBlockBytes) / elementSize / step * step, step);
}

}  // namespace lgh::gl
