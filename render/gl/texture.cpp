#include "render/gl/texture.h"

#include <stdexcept>
#include <string>

namespace lgh::gl {

Texture2D::Texture2D(int width, int height, GLenum internalFormat, int mipLevels)
    : width_(width), height_(height), format_(internalFormat) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("Texture2D: size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  GLuint name = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &name);
  handle_ = Handle<DeleteTexture>(name);
  glTextureStorage2D(name, mipLevels, internalFormat, width, height);
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
