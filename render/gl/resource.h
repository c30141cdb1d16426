#pragma once
// Move-only owners of GL object names, DSA style (glCreate*). Every GL object the engine makes
// lives in one of these, so nothing leaks when a pass throws.

#include <utility>

#include "render/gl/gl.h"

namespace lgh::gl {

template <typename Deleter>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint name) : name_(name) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  GLuint id() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  void reset() {
    if (name_) Deleter{}(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

struct DeleteBuffer {
  void operator()(GLuint n) const { glDeleteBuffers(1, &n); }
};
struct DeleteTexture {
  void operator()(GLuint n) const { glDeleteTextures(1, &n); }
};
struct DeleteFramebuffer {
  void operator()(GLuint n) const { glDeleteFramebuffers(1, &n); }
};
struct DeleteVertexArray {
  void operator()(GLuint n) const { glDeleteVertexArrays(1, &n); }
};
struct DeleteProgram {
  void operator()(GLuint n) const { glDeleteProgram(n); }
};
struct DeleteQuery {
  void operator()(GLuint n) const { glDeleteQueries(1, &n); }
};

using VertexArrayHandle = Handle<DeleteVertexArray>;
using FramebufferHandle = Handle<DeleteFramebuffer>;
using QueryHandle = Handle<DeleteQuery>;

}  // namespace lgh::gl
