#include "render/gl/buffer.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace lgh::gl {

namespace {
// Zero-sized storage is invalid in GL; a 16-byte stub keeps bindings legal.
size_t storageBytes(size_t bytes) { return bytes ? bytes : 16; }
}  // namespace

Buffer::Buffer(Label label, size_t bytes, const void* data, GLbitfield flags)
    : label_(std::move(label)), allocation_(label_, storageBytes(bytes)), bytes_(bytes) {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  handle_ = Handle<DeleteBuffer>(name);
  glNamedBufferStorage(name, GLsizeiptr(storageBytes(bytes)), data, flags);
  const std::string text = label_.text();
  glObjectLabel(GL_BUFFER, name, GLsizei(text.size()), text.c_str());
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

void Buffer::bindBase(GLenum target, GLuint index) const {
  checkStorageBlock(target, bytes_);
  glBindBufferBase(target, index, id());
}

void Buffer::bindRange(GLenum target, GLuint index, size_t offset, size_t bytes) const {
  checkStorageBlock(target, bytes);
  glBindBufferRange(target, index, id(), GLintptr(offset), GLsizeiptr(bytes ? bytes : 16));
}

void Buffer::checkStorageBlock(GLenum target, size_t bytes) const {
  if (target != GL_SHADER_STORAGE_BUFFER || bytes <= kMinStorageBlockBytes) return;
  const size_t limit = maxStorageBlockBytes();
  if (limit > 0 && bytes > limit)
    throw OutOfMemory("GPU memory: " + label_.text() + " binds " + formatBytes(double(bytes)) + label_.sizeNote() +
                      " as one shader storage block, more than the " + formatBytes(double(limit)) +
                      " this device allows (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)");
}

namespace {
void reallocate(Buffer& buffer, const Label& label, size_t bytes, GLbitfield flags) {
  buffer = Buffer();  // the old storage goes before the new is counted against the budget
  buffer = Buffer(label, bytes, nullptr, flags);
}
}  // namespace

bool ensureSize(Buffer& buffer, const Label& label, size_t bytes, GLbitfield flags) {
  if (buffer && buffer.size() >= bytes) return false;
  reallocate(buffer, label, bytes, flags);
  return true;
}

bool fitSize(Buffer& buffer, const Label& label, size_t bytes, GLbitfield flags) {
  if (buffer && buffer.size() == bytes) return false;
  reallocate(buffer, label, bytes, flags);
  return true;
}

size_t maxStorageBlockBytes() {
  // Asked once: the engine's contexts are all of one driver, and bindings check it often.
  static size_t cached = 0;
  if (cached == 0) {
    GLint64 bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &bytes);
    cached = size_t(std::max<GLint64>(bytes, 0));
  }
  return cached;
}

size_t storageBlockElements(size_t elementSize) {
  GLint alignment = 256;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const size_t step = std::max<size_t>(1, size_t(alignment) / elementSize);
  return std::max(std::max(maxStorageBlockBytes(), kMinStorageBlockBytes) / elementSize / step * step, step);
}

}  // namespace lgh::gl
