// EGL contexts without any window system: the device platform (EGL_EXT_platform_device) reaches a
// GPU on a machine with no display; Mesa's surfaceless platform gives llvmpipe or a Mesa GPU driver.
// Both render into FBOs only (EGL_NO_SURFACE), which is all the engine needs.

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

#include "render/gl/context.h"

namespace lgh::gl {
namespace {

std::string eglErrorName(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + std::to_string(error);
  }
}

bool hasToken(const char* list, const char* token) {
  if (!list) return false;
  const size_t n = std::strlen(token);
  for (const char* p = std::strstr(list, token); p; p = std::strstr(p + 1, token))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

template <typename Fn>
Fn eglProc(const char* name) {
  return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

struct DeviceChoice {
  EGLDeviceEXT device = EGL_NO_DEVICE_EXT;
  bool software = true;
};

// Prefers a hardware device; Mesa lists llvmpipe as a device with EGL_MESA_device_software.
DeviceChoice findDevice() {
  DeviceChoice choice;
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasToken(clientExtensions, "EGL_EXT_platform_device")) return choice;
  auto queryDevices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto queryDeviceString = eglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  if (!queryDevices || !queryDeviceString) return choice;
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!queryDevices(16, devices, &count)) return choice;
  for (EGLint i = 0; i < count; ++i) {
    const bool software = hasToken(queryDeviceString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software");
    if (choice.device == EGL_NO_DEVICE_EXT || (choice.software && !software)) choice = {devices[i], software};
  }
  return choice;
}

class EglContext final : public Context {
 public:
  EglContext(EGLDisplay display, const std::string& label, const ContextOptions& options) : display_(display) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor))
      throw ContextError(label + ": eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
    if (!eglBindAPI(EGL_OPENGL_API)) throw ContextError(label + ": the display offers no desktop OpenGL API");
    const char* extensions = eglQueryString(display_, EGL_EXTENSIONS);
    if (!hasToken(extensions, "EGL_KHR_surfaceless_context"))
      throw ContextError(label + ": EGL_KHR_surfaceless_context is missing, cannot render without a surface");

    EGLConfig config = nullptr;
    if (!hasToken(extensions, "EGL_KHR_no_config_context")) {
      const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint numConfigs = 0;
      if (!eglChooseConfig(display_, configAttribs, &config, 1, &numConfigs) || numConfigs == 0)
        throw ContextError(label + ": no EGL config supports desktop OpenGL");
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     options.debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT)
      throw ContextError(label + ": no OpenGL 4.5 core context (" + eglErrorName(eglGetError()) + ")");
    bindToThread();
    initializeGL(reinterpret_cast<void* (*)(const char*)>(eglGetProcAddress), label, options.debug);
  }

  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // The display is not terminated: EGL displays are per process and other contexts may share it.
  }

  void bindToThread() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw ContextError("eglMakeCurrent failed (" + eglErrorName(eglGetError()) + ")");
  }

  Backend backend() const override { return Backend::Egl; }

 private:
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
};

std::unique_ptr<Context> createDeviceContext(const ContextOptions& options, bool requireHardware) {
  auto getPlatformDisplay = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  const DeviceChoice device = findDevice();
  if (!getPlatformDisplay || device.device == EGL_NO_DEVICE_EXT)
    throw ContextError("EGL device platform: no EGL device found (EGL_EXT_platform_device)");
  if (requireHardware && device.software) throw ContextError("EGL device platform: only a software device is present");
  EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device.device, nullptr);
  if (display == EGL_NO_DISPLAY) throw ContextError("EGL device platform: eglGetPlatformDisplayEXT failed");
  return std::make_unique<EglContext>(display, "EGL device", options);
}

std::unique_ptr<Context> createSurfacelessContext(const ContextOptions& options) {
  auto getPlatformDisplay = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!getPlatformDisplay || !hasToken(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_MESA_platform_surfaceless"))
    throw ContextError("EGL surfaceless: EGL_MESA_platform_surfaceless is not available");
  EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) throw ContextError("EGL surfaceless: eglGetPlatformDisplayEXT failed");
  return std::make_unique<EglContext>(display, "EGL surfaceless", options);
}

}  // namespace

std::unique_ptr<Context> createEglContext(Backend which, const ContextOptions& options) {
  if (which == Backend::EglDevice) return createDeviceContext(options, /*requireHardware=*/false);
  if (which == Backend::EglSurfaceless) return createSurfacelessContext(options);
  // Plain "egl": a hardware device if there is one, else Mesa's surfaceless platform, else whatever device exists.
  std::string failures;
  for (int attempt = 0; attempt < 3; ++attempt) {
    try {
      if (attempt == 0) return createDeviceContext(options, /*requireHardware=*/true);
      if (attempt == 1) return createSurfacelessContext(options);
      return createDeviceContext(options, /*requireHardware=*/false);
    } catch (const ContextError& e) {
      failures += (failures.empty() ? "" : "; ") + std::string(e.what());
    }
  }
  throw ContextError(failures);
}

}  // namespace lgh::gl
