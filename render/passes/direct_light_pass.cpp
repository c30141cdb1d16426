#include "render/passes/direct_light_pass.h"

#include <algorithm>
#include <vector>

#include "render/gl/debug.h"
#include "shared/bindings.h"

namespace lgh {

DirectLightPass::DirectLightPass() : program_(gl::Program::compute("direct_light.comp")) {}

void DirectLightPass::execute(const SceneGpu& scene, const GBuffer& gbuffer, bool shadows, bool skipPointLights,
                              gl::Texture2D& out) {
  scene.bindForCompute();
  size_t lightCount = scene.punctualLights().size();
  if (skipPointLights) {
    // Thousands of point lights go through the LGH; looping over them here only to skip each one
    // would cost more than shading them (seconds on llvmpipe for 4,096).
    if (!nonPointLightsUploaded_) {
      std::vector<gpu::GpuPunctualLight> lights;
      for (const gpu::GpuPunctualLight& l : scene.punctualLights())
        if (l.type != gpu::kLightPoint) lights.push_back(l);
      nonPointLightCount_ = lights.size();
      lights.resize(std::max<size_t>(lights.size(), 1));  // a buffer is never empty
      nonPointLights_ = gl::Buffer::fromVector(lights, 0);
      nonPointLightsUploaded_ = true;
    }
    nonPointLights_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PUNCTUAL_LIGHTS);
    lightCount = nonPointLightCount_;
  }
  gbuffer.bindForReading();
  out.bindImage(0, GL_WRITE_ONLY);
  program_.set("lightCount", unsigned(lightCount));
  program_.set("shadows", int(shadows));
  program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  gl::checkErrors("direct light pass");
}

}  // namespace lgh
