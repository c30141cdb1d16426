#pragma once
// 2-D textures with immutable storage, buffers read as texels, and a framebuffer that bundles a set of
// 2-D textures.

#include <glm/glm.hpp>
#include <initializer_list>
#include <vector>

#include "render/gl/buffer.h"
#include "render/gl/memory.h"
#include "render/gl/resource.h"

namespace lgh::gl {

class Texture2D {
 public:
  Texture2D() = default;
  // Throws gl::OutOfMemory when the bytes exceed the memory budget (gl/memory.h).
  Texture2D(Label label, int width, int height, GLenum internalFormat, int mipLevels = 1);

  GLuint id() const { return handle_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  GLenum format() const { return format_; }
  const Label& label() const { return label_; }
  explicit operator bool() const { return bool(handle_); }

  void setFilter(GLenum minFilter, GLenum magFilter);
  void setWrap(GLenum wrap);
  void upload(GLenum format, GLenum type, const void* pixels);
  void clear(const glm::vec4& value);
  void clearUint(GLuint value);
  // Reads level 0 as RGBA floats, rows bottom-up as GL stores them.
  std::vector<glm::vec4> readRGBA() const;
  std::vector<GLuint> readUint() const;  // for R32UI textures

  void bindTexture(GLuint unit) const;
  void bindImage(GLuint unit, GLenum access) const;

 private:
  Label label_;
  Allocation allocation_;
  Handle<DeleteTexture> handle_;
  int width_ = 0, height_ = 0;
  GLenum format_ = 0;
};

// A buffer's bytes read as texels (texelFetch on a samplerBuffer / usamplerBuffer) in a 16-byte format,
// GL_RGBA32F or GL_RGBA32UI; the buffer must outlive its attachment. Two of these over one buffer read its
// float and its integer fields (a float view could flush the denormal bit patterns that small integers
// make).
class BufferTexture {
 public:
  BufferTexture() = default;
  explicit BufferTexture(GLenum internalFormat);
  BufferTexture(const Buffer& buffer, GLenum internalFormat) : BufferTexture(internalFormat) { attach(buffer); }

  // Reads the buffer's first `bytes` (0: all of it). Throws gl::OutOfMemory when they are more texels than
  // GL_MAX_TEXTURE_BUFFER_SIZE.
  void attach(const Buffer& buffer, size_t bytes = 0);
  void bindTexture(GLuint unit) const { glBindTextureUnit(unit, handle_.id()); }
  // As an image (imageBuffer) a shader writes or reads texel by texel.
  void bindImage(GLuint unit, GLenum access) const {
    glBindImageTexture(unit, handle_.id(), 0, GL_FALSE, 0, access, format_);
  }

 private:
  Handle<DeleteTexture> handle_;
  GLenum format_ = 0;
};

// Bytes of storage a texture of this format, size and mip chain takes (as laid out unpadded).
size_t textureBytes(GLenum internalFormat, int width, int height, int mipLevels = 1);

class Framebuffer {
 public:
  Framebuffer() = default;
  // Attaches colour textures in order (location i = GL_COLOR_ATTACHMENT0 + i) and an optional depth texture
  // (as depth and stencil when its format has stencil).
  Framebuffer(std::initializer_list<const Texture2D*> colors, const Texture2D* depth);

  GLuint id() const { return handle_.id(); }
  void bind() const;

 private:
  FramebufferHandle handle_;
  int width_ = 0, height_ = 0;
};

}  // namespace lgh::gl
