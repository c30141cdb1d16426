#include "render/gl/texture.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace lgh::gl {

namespace {
size_t bytesPerTexel(GLenum format) {
  switch (format) {
    case GL_RGBA32F:
      return 16;
    case GL_RGBA16F:
    case GL_RG32F:
    case GL_DEPTH32F_STENCIL8:  // 32-bit depth beside 8 bits of stencil, padded to 64 bits
      return 8;
    case GL_R32F:
    case GL_R32UI:
    case GL_RGBA8:
    case GL_SRGB8_ALPHA8:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
      return 4;
    default:
      throw std::invalid_argument("Texture2D: no size known for internal format " + std::to_string(format) +
                                  " (add it to gl/texture.cpp)");
  }
}

int checkedSize(int size, int other) {
  if (size <= 0 || other <= 0)
    throw std::invalid_argument("Texture2D: size must be positive, got " + std::to_string(size) + "x" +
                                std::to_string(other));
  return size;
}
}  // namespace

BufferTexture::BufferTexture(GLenum internalFormat) : format_(internalFormat) {
  if (internalFormat != GL_RGBA32F && internalFormat != GL_RGBA32UI)
    throw std::invalid_argument("BufferTexture: 16-byte texels only (GL_RGBA32F, GL_RGBA32UI)");
  GLuint name = 0;
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &name);
  handle_ = Handle<DeleteTexture>(name);
}

void BufferTexture::attach(const Buffer& buffer, size_t bytes) {
  // Asked once, as maxStorageBlockBytes is: the contexts are all of one driver, and passes attach every frame.
  static const GLint maxTexels = [] {
    GLint texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    return texels;
  }();
  if (bytes == 0 || bytes > buffer.size()) bytes = buffer.size();
  const size_t texels = bytes / 16;
  if (texels > size_t(std::max(maxTexels, 0)))
    throw OutOfMemory("GPU memory: " + buffer.label().text() + " is read as " + std::to_string(texels) +
                      " texels, more than the " + std::to_string(maxTexels) +
                      " one texture buffer may have here (GL_MAX_TEXTURE_BUFFER_SIZE)");
  // A range of at least one texel (an empty buffer's storage is a 16-byte stub: gl/buffer.cpp).
  glTextureBufferRange(handle_.id(), format_, buffer.id(), 0, GLsizeiptr(std::max<size_t>(bytes, 16)));
}

size_t textureBytes(GLenum internalFormat, int width, int height, int mipLevels) {
  size_t texels = 0;
  for (int level = 0; level < mipLevels; ++level)
    texels += size_t(std::max(width >> level, 1)) * size_t(std::max(height >> level, 1));
  return texels * bytesPerTexel(internalFormat);
}

Texture2D::Texture2D(Label label, int width, int height, GLenum internalFormat, int mipLevels)
    : label_(std::move(label)),
      allocation_(label_, textureBytes(internalFormat, checkedSize(width, height), height, mipLevels)),
      width_(width),
      height_(height),
      format_(internalFormat) {
  GLuint name = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &name);
  handle_ = Handle<DeleteTexture>(name);
  glTextureStorage2D(name, mipLevels, internalFormat, width, height);
  const std::string text = label_.text();
  glObjectLabel(GL_TEXTURE, name, GLsizei(text.size()), text.c_str());
  setFilter(GL_NEAREST, GL_NEAREST);
  setWrap(GL_CLAMP_TO_EDGE);
}

void Texture2D::setFilter(GLenum minFilter, GLenum magFilter) {
  glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, GLint(minFilter));
  glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, GLint(magFilter));
}

void Texture2D::setWrap(GLenum wrap) {
  glTextureParameteri(id(), GL_TEXTURE_WRAP_S, GLint(wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_T, GLint(wrap));
}

void Texture2D::upload(GLenum format, GLenum type, const void* pixels) {
  glTextureSubImage2D(id(), 0, 0, 0, width_, height_, format, type, pixels);
}

void Texture2D::clear(const glm::vec4& value) { glClearTexImage(id(), 0, GL_RGBA, GL_FLOAT, &value[0]); }

void Texture2D::clearUint(GLuint value) { glClearTexImage(id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &value); }

std::vector<glm::vec4> Texture2D::readRGBA() const {
  std::vector<glm::vec4> pixels(size_t(width_) * size_t(height_));
  glGetTextureImage(id(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
  return pixels;
}

std::vector<GLuint> Texture2D::readUint() const {
  std::vector<GLuint> pixels(size_t(width_) * size_t(height_));
  glGetTextureImage(id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(pixels.size() * sizeof(GLuint)), pixels.data());
  return pixels;
}

void Texture2D::bindTexture(GLuint unit) const { glBindTextureUnit(unit, id()); }

void Texture2D::bindImage(GLuint unit, GLenum access) const {
  glBindImageTexture(unit, id(), 0, GL_FALSE, 0, access, format_);
}

Framebuffer::Framebuffer(std::initializer_list<const Texture2D*> colors, const Texture2D* depth) {
  GLuint name = 0;
  glCreateFramebuffers(1, &name);
  handle_ = FramebufferHandle(name);
  std::vector<GLenum> drawBuffers;
  for (const Texture2D* color : colors) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(drawBuffers.size());
    glNamedFramebufferTexture(name, attachment, color->id(), 0);
    drawBuffers.push_back(attachment);
    width_ = color->width();
    height_ = color->height();
  }
  if (depth) {
    const bool stencil = depth->format() == GL_DEPTH32F_STENCIL8 || depth->format() == GL_DEPTH24_STENCIL8;
    glNamedFramebufferTexture(name, stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depth->id(), 0);
    width_ = depth->width();
    height_ = depth->height();
  }
  glNamedFramebufferDrawBuffers(name, GLsizei(drawBuffers.size()), drawBuffers.data());
  const GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("framebuffer incomplete (status 0x" + std::to_string(status) + ")");
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, id());
  glViewport(0, 0, width_, height_);
}

}  // namespace lgh::gl
