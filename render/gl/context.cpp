#include "render/gl/context.h"

#include <algorithm>
#include <sstream>

#include "render/gl/debug.h"
#include "render/gl/gl.h"

namespace lgh::gl {
namespace {

struct BackendName {
  Backend backend;
  const char* name;
};
constexpr BackendName kBackendNames[] = {
    {Backend::Auto, "auto"},
    {Backend::Egl, "egl"},
    {Backend::EglDevice, "egl-device"},
    {Backend::EglSurfaceless, "egl-surfaceless"},
    {Backend::OSMesa, "osmesa"},
    {Backend::Window, "window"},
};

std::string alternatives() {
  std::string list;
  for (const auto& b : kBackendNames) list += (list.empty() ? "" : ", ") + std::string(b.name);
  return list;
}

}  // namespace

Backend parseBackend(const std::string& name) {
  for (const auto& b : kBackendNames)
    if (name == b.name) return b.backend;
  throw ContextError("unknown backend '" + name + "' (choose one of: " + alternatives() + ")");
}

std::string backendName(Backend backend) {
  for (const auto& b : kBackendNames)
    if (b.backend == backend) return b.name;
  return "?";
}

std::vector<std::string> backendNames() {
  std::vector<std::string> names;
  for (const auto& b : kBackendNames) names.push_back(b.name);
  return names;
}

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
  switch (options.backend) {
    case Backend::Egl:
    case Backend::EglDevice:
    case Backend::EglSurfaceless:
      return createEglContext(options.backend, options);
    case Backend::OSMesa:
      return createOSMesaContext(options);
    case Backend::Window:
      return createWindowContext(options);
    case Backend::Auto:
      break;
  }
  // Auto: EGL first (it reaches real GPUs), OSMesa as the software fallback.
  std::string failures;
  try {
    return createEglContext(Backend::Egl, options);
  } catch (const ContextError& e) {
    failures += std::string("\n  egl: ") + e.what();
  }
  try {
    return createOSMesaContext(options);
  } catch (const ContextError& e) {
    failures += std::string("\n  osmesa: ") + e.what();
  }
  throw ContextError(
      "no headless OpenGL 4.5 core context could be created:" + failures +
      "\n(install libegl-mesa0 and libgl1-mesa-dri for EGL, libosmesa6 for OSMesa, or pick one with --backend: " +
      alternatives() + ")");
}

namespace {
const Context* glLoadedFor = nullptr;  // the context whose entry points glad currently holds
}

void Context::makeCurrent() {
  bindToThread();
  if (glLoadedFor != this && getProcAddress_) {
    gladLoadGL(reinterpret_cast<GLADloadfunc>(getProcAddress_));
    glLoadedFor = this;
  }
}

Context::~Context() {
  if (glLoadedFor == this) glLoadedFor = nullptr;
}

void Context::initializeGL(void* (*getProcAddress)(const char*), const std::string& backendLabel, bool debug) {
  getProcAddress_ = getProcAddress;
  glLoadedFor = this;
  int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(getProcAddress));
  if (version == 0) throw ContextError(backendLabel + ": could not load OpenGL entry points");
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 45) {
    std::ostringstream msg;
    msg << backendLabel << ": OpenGL 4.5 core is required, the context offers " << GLAD_VERSION_MAJOR(version) << "."
        << GLAD_VERSION_MINOR(version);
    throw ContextError(msg.str());
  }
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    extensions_.emplace_back(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))));
  std::sort(extensions_.begin(), extensions_.end());
  label_ = backendLabel + ": " + reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", OpenGL " +
           reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (debug) installDebugOutput();
  checkErrors("context creation");
}

std::string Context::description() const { return label_; }

bool Context::hasExtension(const std::string& name) const {
  return std::binary_search(extensions_.begin(), extensions_.end(), name);
}

}  // namespace lgh::gl
