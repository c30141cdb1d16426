#include "render/passes/gbuffer_pass.h"

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {

GBuffer::GBuffer(int w, int h)
    : width(w),
      height(h),
      position({passes::kGBuffer, "position", kImageSize}, w, h, GL_RGBA32F),
      normal({passes::kGBuffer, "normal", kImageSize}, w, h, GL_RGBA16F),
      albedo({passes::kGBuffer, "albedo", kImageSize}, w, h, GL_RGBA16F),
      emission({passes::kGBuffer, "emission", kImageSize}, w, h, GL_RGBA16F),
      depth({passes::kGBuffer, "depth", kImageSize}, w, h, GL_DEPTH_COMPONENT32F),
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
  // Reversed Z (render/camera_view.h): depth 1 at the near plane, cleared to 0 (infinitely far), the
  // nearer surface has the greater depth; [0, 1] clip depth so the float buffer keeps its precision.
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glClearNamedFramebufferfi(out.framebuffer.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDisable(GL_BLEND);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  program_.use();
  scene.drawByMaterial([&](std::uint32_t index, const gpu::GpuMaterial& m) {
    // glTF: single-sided materials are invisible from behind; double-sided ones are seen from both sides.
    if (scene.scene().materials[index].doubleSided)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    program_.set("baseColorFactor", m.baseColorFactor);
    program_.set("emission", m.emission);
    program_.set("alphaCutoff", m.alphaCutoff);
    program_.set("baseColorTexCoord", m.baseColorTexCoord);
    program_.set("emissiveTexCoord", m.emissiveTexCoord);
    program_.set("baseColorUvRow0", m.baseColorUvRow0);
    program_.set("baseColorUvRow1", m.baseColorUvRow1);
    program_.set("emissiveUvRow0", m.emissiveUvRow0);
    program_.set("emissiveUvRow1", m.emissiveUvRow1);
    scene.texture(m.baseColorTexture).bindTexture(LGH_TEXTURE_MATERIAL_BASE_COLOR);
    scene.texture(m.emissiveTexture).bindTexture(LGH_TEXTURE_MATERIAL_EMISSIVE);
  });
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);  // other passes use GL's default
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::checkErrors("G-buffer pass");
}

}  // namespace lgh
