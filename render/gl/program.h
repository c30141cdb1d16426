#pragma once
// GLSL programs built from the shader tree in glsl/. Sources are embedded in the binary at build time
// (LGH_SHADER_DIR overrides them from disk). `#include "shared/x.h"` is resolved here, once per file,
// so the structs in glsl/shared/ are written once and compiled by both C++ and GLSL.

#include <glm/glm.hpp>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "render/gl/resource.h"

namespace lgh::gl {

using Defines = std::vector<std::pair<std::string, std::string>>;

// The fully expanded source of a shader file with `defines` injected after #version.
std::string expandShaderSource(const std::string& path, const Defines& defines = {});

class Program {
 public:
  Program() = default;
  static Program compute(const std::string& path, const Defines& defines = {});
  static Program graphics(const std::string& vertexPath, const std::string& fragmentPath, const Defines& defines = {});

  GLuint id() const { return handle_.id(); }
  explicit operator bool() const { return bool(handle_); }
  void use() const { glUseProgram(id()); }

  // Uniform setters by name; a uniform the compiler optimised away is silently ignored, as in GL.
  void set(const char* name, float v) const { glProgramUniform1f(id(), location(name), v); }
  void set(const char* name, int v) const { glProgramUniform1i(id(), location(name), v); }
  void set(const char* name, unsigned v) const { glProgramUniform1ui(id(), location(name), v); }
  void set(const char* name, const glm::vec2& v) const { glProgramUniform2fv(id(), location(name), 1, &v[0]); }
  void set(const char* name, const glm::vec3& v) const { glProgramUniform3fv(id(), location(name), 1, &v[0]); }
  void set(const char* name, const glm::vec4& v) const { glProgramUniform4fv(id(), location(name), 1, &v[0]); }
  void set(const char* name, const glm::ivec2& v) const { glProgramUniform2iv(id(), location(name), 1, &v[0]); }
  void set(const char* name, const glm::uvec2& v) const { glProgramUniform2uiv(id(), location(name), 1, &v[0]); }
  void set(const char* name, const glm::mat4& m) const {
    glProgramUniformMatrix4fv(id(), location(name), 1, GL_FALSE, &m[0][0]);
  }

  // Compute only: dispatches ceil(count / localSize) groups in x, folding into y past the
  // 65535-group limit; the shader must then use lghGlobalIndex() from shared/dispatch.glsl.
  void dispatch1D(size_t invocations, unsigned localSize) const;
  void dispatch2D(int width, int height, glm::uvec2 localSize) const;

 private:
  explicit Program(GLuint name) : handle_(name) {}
  GLint location(const char* name) const;

  Handle<DeleteProgram> handle_;
  mutable std::unordered_map<std::string, GLint> locations_;
};

}  // namespace lgh::gl
