#pragma once
// One small interface over the three ways we get an OpenGL 4.5 core context:
// EGL (device platform for a GPU without a display, or Mesa's surfaceless platform), OSMesa,
// and a GLFW window for the viewer. Everything after creation is the same GL code.

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace lgh::gl {

enum class Backend {
  Auto,            // EGL (a hardware device if one exists, else surfaceless), then OSMesa
  Egl,             // EGL device platform with a hardware device, else surfaceless
  EglDevice,       // EGL_EXT_platform_device only (e.g. an NVIDIA GPU without a display)
  EglSurfaceless,  // EGL_MESA_platform_surfaceless only
  OSMesa,          // Mesa's off-screen library
  Window,          // GLFW window (needs a display)
};

// "auto", "egl", "egl-device", "egl-surfaceless", "osmesa", "window"; throws with the alternatives.
Backend parseBackend(const std::string& name);
std::string backendName(Backend backend);
std::vector<std::string> backendNames();

struct ContextOptions {
  Backend backend = Backend::Auto;
  bool debug = false;  // KHR_debug output, synchronous; GL errors are recorded and raised by checkErrors()
  // Window backend only:
  int windowWidth = 1280, windowHeight = 720;
  std::string windowTitle = "lgh";
  bool windowVisible = true;
};

struct ContextError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Context {
 public:
  virtual ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Creates the context, makes it current, loads GL and checks for 4.5 core. Throws ContextError
  // naming the backend that failed and why, and the alternatives to try.
  static std::unique_ptr<Context> create(const ContextOptions& options = {});

  // Makes the context current on this thread. glad's entry points are process-wide and OSMesa and
  // EGL hand out different ones, so they are reloaded when a different context becomes current.
  void makeCurrent();
  virtual Backend backend() const = 0;
  // e.g. "EGL surfaceless: llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6"
  std::string description() const;
  virtual GLFWwindow* window() { return nullptr; }  // Window backend only

  bool hasExtension(const std::string& name) const;

 protected:
  Context() = default;
  // Called by each backend once its context is current: loads glad, checks the version, sets up debug output.
  void initializeGL(void* (*getProcAddress)(const char*), const std::string& backendLabel, bool debug);
  virtual void bindToThread() = 0;  // the backend's own make-current call

 private:
  void* (*getProcAddress_)(const char*) = nullptr;
  std::string label_;
  std::vector<std::string> extensions_;
};

// Backend constructors (one file each). They throw ContextError when unavailable.
std::unique_ptr<Context> createEglContext(Backend which, const ContextOptions& options);
std::unique_ptr<Context> createOSMesaContext(const ContextOptions& options);
std::unique_ptr<Context> createWindowContext(const ContextOptions& options);

}  // namespace lgh::gl
