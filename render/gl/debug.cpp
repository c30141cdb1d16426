#include "render/gl/debug.h"

#include <string>

#include "render/gl/gl.h"

namespace lgh::gl {
namespace {

// Errors reported by the driver since the last checkErrors(). One GL context per thread is the
// engine's model, so thread-local storage is the right scope.
thread_local std::string pendingErrors;

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                               const GLchar* message, const void*) {
  (void)id;
  (void)length;
  // Compile and link failures are already raised by Program with the full log and file names.
  if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
  if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
  if (pendingErrors.size() < 4096) pendingErrors += std::string(pendingErrors.empty() ? "" : "; ") + message;
}

const char* errorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    default:
      return "unknown GL error";
  }
}

}  // namespace

void installDebugOutput() {
  glEnable(GL_DEBUG_OUTPUT);
  // Synchronous, so the message arrives inside the offending call and names it in order.
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

void checkErrors(const char* where) {
  std::string messages;
  messages.swap(pendingErrors);
  for (GLenum error = glGetError(); error != GL_NO_ERROR; error = glGetError())
    messages += std::string(messages.empty() ? "" : "; ") + errorName(error);
  if (!messages.empty()) throw Error(std::string(where) + ": " + messages);
}

DebugGroup::DebugGroup(const char* name) { glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name); }
DebugGroup::~DebugGroup() { glPopDebugGroup(); }

}  // namespace lgh::gl
