#include "render/passes/direct_light_pass.h"

#include <algorithm>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {

DirectLightPass::DirectLightPass() : program_("direct_light.comp") {}

void DirectLightPass::execute(const SceneGpu& scene, const GBuffer& gbuffer, bool shadows, bool skipPointLights,
                              gl::Texture2D& out) {
  scene.bindForCompute();
  size_t lightCount = scene.punctualLights().size();
  if (skipPointLights) {
    // Thousands of point lights go through the LGH; looping over them here only to skip each one
    // would cost more than shading them (seconds on llvmpipe for 4,096).
    if (!nonPointLightsUploaded_ || nonPointLightsVersion_ != scene.lightsVersion()) {
      std::vector<gpu::GpuPunctualLight> lights;
      for (const gpu::GpuPunctualLight& l : scene.punctualLights())
        if (l.type != gpu::kLightPoint) lights.push_back(l);
      nonPointLightCount_ = lights.size();
      lights.resize(std::max<size_t>(lights.size(), 1));  // a buffer is never empty
      nonPointLights_ = gl::Buffer::fromVector({passes::kDirectLight, "non-point lights"}, lights, 0);
      nonPointLightsUploaded_ = true;
      nonPointLightsVersion_ = scene.lightsVersion();
    }
    nonPointLights_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PUNCTUAL_LIGHTS);
    lightCount = nonPointLightCount_;
  }
  gbuffer.bindForReading();
  out.bindImage(LGH_IMAGE_DIRECT, GL_READ_WRITE);
  const gl::Program& program = program_(scene);
  program.set("shadows", int(shadows));
  // A few lights per dispatch: llvmpipe ends an invocation's loops after 65,535 iterations in all,
  // and every light's shadow ray walks the BVH (hundreds of iterations in Sponza).
  constexpr size_t kLightsPerDispatch = 32;
  size_t first = 0;
  do {
    const size_t n = std::min(kLightsPerDispatch, lightCount - first);
    program.set("firstLight", unsigned(first));
    program.set("lightCount", unsigned(n));
    program.set("accumulate", int(first > 0));
    program.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    first += n;
  } while (first < lightCount);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  gl::checkErrors("direct light pass");
}

}  // namespace lgh
