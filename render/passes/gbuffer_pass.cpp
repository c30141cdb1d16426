#include "render/passes/gbuffer_pass.h"

#include "render/gl/debug.h"
#include "shared/bindings.h"

namespace lgh {

GBuffer::GBuffer(int w, int h)
    : width(w),
      height(h),
      position(w, h, GL_RGBA32F),
      normal(w, h, GL_RGBA16F),
      albedo(w, h, GL_RGBA16F),
      emission(w, h, GL_RGBA16F),
      depth(w, h, GL_DEPTH_COMPONENT32F),
      framebuffer({&position, &normal, &albedo, &emission}, &depth) {}

void GBuffer::bindForReading() const {
  position.bindTexture(LGH_TEXTURE_GBUFFER_POSITION);
  normal.bindTexture(LGH_TEXTURE_GBUFFER_NORMAL);
  albedo.bindTexture(LGH_TEXTURE_GBUFFER_ALBEDO);
  emission.bindTexture(LGH_TEXTURE_GBUFFER_EMISSION);
}

GBufferPass::GBufferPass() : program_(gl::Program::graphics("gbuffer.vert", "gbuffer.frag")) {}

void GBufferPass::execute(const SceneGpu& scene, GBuffer& out) const {
  out.framebuffer.bind();
  const float zero[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(out.framebuffer.id(), GL_COLOR, i, zero);
  glClearNamedFramebufferfi(out.framebuffer.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // glTF materials may be double-sided; the shader flips normals to the viewer
  glDisable(GL_BLEND);
  program_.use();
  scene.drawByMaterial([&](std::uint32_t, const gpu::GpuMaterial& m) {
    program_.set("baseColorFactor", m.baseColorFactor);
    program_.set("emissionFactor", m.emission);
    scene.texture(m.baseColorTexture).bindTexture(LGH_TEXTURE_MATERIAL_BASE_COLOR);
    scene.texture(m.emissiveTexture).bindTexture(LGH_TEXTURE_MATERIAL_EMISSIVE);
  });
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::checkErrors("G-buffer pass");
}

}  // namespace lgh
