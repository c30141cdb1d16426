#include "render/passes/direct_light_pass.h"

#include "render/gl/debug.h"

namespace lgh {

DirectLightPass::DirectLightPass() : program_(gl::Program::compute("direct_light.comp")) {}

void DirectLightPass::execute(const SceneGpu& scene, const GBuffer& gbuffer, bool shadows, bool skipPointLights,
                              gl::Texture2D& out) const {
  scene.bindForCompute();
  gbuffer.bindForReading();
  out.bindImage(0, GL_WRITE_ONLY);
  program_.set("lightCount", unsigned(scene.punctualLights().size()));
  program_.set("shadows", int(shadows));
  program_.set("skipPointLights", int(skipPointLights));
  program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  gl::checkErrors("direct light pass");
}

}  // namespace lgh
