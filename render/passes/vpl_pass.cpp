#include "render/passes/vpl_pass.h"

#include <algorithm>
#include <stdexcept>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/lgh_types.h"

namespace lgh {

VplPass::VplPass(const SceneGpu& scene)
    : scene_(scene),
      allEmitters_(buildEmitterTable(scene.scene(), scene.lights())),
      triangleEmitters_(buildEmissiveTriangleTable(scene.scene())),
      allEmitterBuffer_(gl::Buffer::fromVector(allEmitters_.emitters, 0)),
      triangleEmitterBuffer_(gl::Buffer::fromVector(triangleEmitters_.emitters, 0)),
      counter_(sizeof(GLuint)),
      emittersLightsVersion_(scene.lightsVersion()),
      paths_(gl::Program::compute("vpl_generate.comp", {{"LGH_VPL_PATHS", "1"}})),
      emitterSamples_(gl::Program::compute("vpl_generate.comp", {{"LGH_EMITTER_SAMPLES", "1"}})) {}

size_t VplPass::run(const gl::Program& program, const gl::Buffer& emitters, gl::Buffer& out, size_t offset,
                    size_t capacity, size_t samples, int bounces, std::uint32_t seed) {
  if (offset + capacity > out.size() / sizeof(gpu::GpuLight))
    throw std::out_of_range("VplPass: the output buffer is too small");
  if (samples == 0) return 0;
  scene_.bindForCompute();
  emitters.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  out.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  counter_.clear();
  counter_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  const Bounds& b = scene_.scene().bounds;
  program.set("sampleCount", GLuint(samples));
  program.set("maxBounces", GLuint(bounces));
  program.set("seed", GLuint(seed));
  program.set("outputOffset", GLuint(offset));
  program.set("outputCapacity", GLuint(capacity));
  program.set("sceneSphere", glm::vec4(b.center(), std::max(0.5f * b.diagonal(), 1e-6f)));
  program.dispatch1D(samples, 64);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  gl::checkErrors("VPL generation");
  return std::min<size_t>(counter_.download<GLuint>(1)[0], capacity);
}

void VplPass::updateEmitters() {
  if (emittersLightsVersion_ == scene_.lightsVersion()) return;
  // A moved light keeps its power, but a changed intensity or cone changes every selection
  // probability, so the whole table is rebuilt (on a light edit, not per frame; cheap next to tracing
  // the paths it feeds).
  allEmitters_ = buildEmitterTable(scene_.scene(), scene_.lights());
  allEmitterBuffer_ = gl::Buffer::fromVector(allEmitters_.emitters, 0);
  emittersLightsVersion_ = scene_.lightsVersion();
}

size_t VplPass::tracePaths(gl::Buffer& out, size_t offset, size_t budget, int bounces, std::uint32_t seed) {
  updateEmitters();
  if (bounces < 1 || allEmitters_.empty()) return 0;
  return run(paths_, allEmitterBuffer_, out, offset, maxVplCount(budget, bounces), pathCount(budget, bounces), bounces,
             seed);
}

size_t VplPass::sampleEmissiveTriangles(gl::Buffer& out, size_t offset, size_t count, std::uint32_t seed) {
  if (triangleEmitters_.empty()) return 0;
  return run(emitterSamples_, triangleEmitterBuffer_, out, offset, count, count, 1, seed);
}

}  // namespace lgh
