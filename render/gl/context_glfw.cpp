// A GLFW window with an OpenGL 4.5 core context: the viewer's backend. Needs a display (X11 or
// Wayland, or Xvfb); without one glfwInit fails and we say so plainly.

#include <GLFW/glfw3.h>

#include <string>

#include "render/gl/context.h"

namespace lgh::gl {
namespace {

thread_local std::string lastGlfwError;
void onGlfwError(int, const char* description) { lastGlfwError = description; }

class WindowContext final : public Context {
 public:
  explicit WindowContext(const ContextOptions& options) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit())
      throw ContextError("GLFW window: glfwInit failed (" + lastGlfwError +
                         "); a window needs a display: set DISPLAY, run under xvfb-run, or use a headless backend "
                         "(--backend egl or osmesa)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.windowVisible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    window_ =
        glfwCreateWindow(options.windowWidth, options.windowHeight, options.windowTitle.c_str(), nullptr, nullptr);
    if (!window_) {
      std::string why = lastGlfwError;
      glfwTerminate();
      throw ContextError("GLFW window: no OpenGL 4.5 core context (" + why + ")");
    }
    bindToThread();
    glfwSwapInterval(0);
    initializeGL(reinterpret_cast<void* (*)(const char*)>(glfwGetProcAddress), "GLFW window", options.debug);
  }
  ~WindowContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }

  void bindToThread() override { glfwMakeContextCurrent(window_); }
  Backend backend() const override { return Backend::Window; }
  GLFWwindow* window() override { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<Context> createWindowContext(const ContextOptions& options) {
  return std::make_unique<WindowContext>(options);
}

}  // namespace lgh::gl
