// OSMesa: Mesa's off-screen software renderer, a context with no window system at all.
// The engine renders into FBOs, so the OSMesa colour buffer is a 1x1 placeholder.

#include <GL/osmesa.h>

#include "render/gl/context.h"

namespace lgh::gl {
namespace {

class OSMesaContextImpl final : public Context {
 public:
  explicit OSMesaContextImpl(const ContextOptions& options) {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!context_) throw ContextError("OSMesa: OSMesaCreateContextAttribs returned no OpenGL 4.5 core context");
    bindToThread();
    initializeGL(reinterpret_cast<void* (*)(const char*)>(OSMesaGetProcAddress), "OSMesa", options.debug);
  }
  ~OSMesaContextImpl() override { OSMesaDestroyContext(context_); }

  void bindToThread() override {
    if (!OSMesaMakeCurrent(context_, placeholder_, GL_UNSIGNED_BYTE, 1, 1))
      throw ContextError("OSMesa: OSMesaMakeCurrent failed");
  }
  Backend backend() const override { return Backend::OSMesa; }

 private:
  OSMesaContext context_ = nullptr;
  unsigned char placeholder_[4] = {};
};

}  // namespace

std::unique_ptr<Context> createOSMesaContext(const ContextOptions& options) {
  return std::make_unique<OSMesaContextImpl>(options);
}

}  // namespace lgh::gl
