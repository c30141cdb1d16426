#include "render/passes/vpl_pass.h"

#include <algorithm>
#include <stdexcept>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/lgh_types.h"

namespace lgh {

VplPass::VplPass(const SceneGpu& scene)
    : scene_(scene),
      allEmitters_(buildEmitterTable(scene.scene(), scene.lights())),
      triangleEmitters_(buildEmissiveTriangleTable(scene.scene())),
      allEmitterBuffer_(gl::Buffer::fromVector({passes::kInputLights, "emitters"}, allEmitters_.emitters, 0)),
      triangleEmitterBuffer_(
          gl::Buffer::fromVector({passes::kInputLights, "emissive triangles"}, triangleEmitters_.emitters, 0)),
      emittersLightsVersion_(scene.lightsVersion()),
      emittersGeometryVersion_(scene.geometryVersion()),
      paths_("vpl_generate.comp", {{"LGH_VPL_PATHS", "1"}}),
      emitterSamples_("vpl_generate.comp", {{"LGH_EMITTER_SAMPLES", "1"}}),
      compactFlags_(gl::Program::compute("vpl_compact.comp", {{"LGH_COMPACT_FLAGS", "1"}})),
      compactWrite_(gl::Program::compute("vpl_compact.comp", {{"LGH_COMPACT_WRITE", "1"}})) {}

namespace {
// Binds lights [offset, offset + count) of `lights` (GpuLight) to `binding` from the nearest offset below that
// a storage binding may start at; returns where `offset` falls in the bound range.
GLuint bindLightRange(const gl::Buffer& lights, size_t offset, size_t count, GLuint binding) {
  GLint alignment = 256;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const size_t step = std::max<size_t>(size_t(std::max(alignment, 1)), sizeof(gpu::GpuLight));  // powers of 2
  const size_t base = offset * sizeof(gpu::GpuLight) / step * step;
  const size_t end = std::min((offset + count) * sizeof(gpu::GpuLight), lights.size());
  lights.bindRange(GL_SHADER_STORAGE_BUFFER, binding, base, end - base);
  return GLuint(offset - base / sizeof(gpu::GpuLight));
}
}  // namespace

size_t VplPass::batchSamples(int bounces) const {
  GLint alignment = 256;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const size_t records = gl::storageBlockElements(sizeof(gpu::GpuLight));
  const size_t slack = size_t(std::max(alignment, 1)) / sizeof(gpu::GpuLight) + 1;
  const size_t samples = std::max<size_t>((records - std::min(slack, records - 1)) / size_t(std::max(bounces, 1)), 1);
  return batchLimit_ > 0 ? std::min(samples, batchLimit_) : samples;
}

void VplPass::generate(const gl::Program& program, const gl::Buffer& emitters, gl::Buffer& out, size_t offset,
                       size_t first, size_t count, size_t total, int bounces, std::uint32_t seed) {
  if (offset + count * size_t(bounces) > out.size() / sizeof(gpu::GpuLight))
    throw std::out_of_range("VplPass: the output buffer is too small");
  scene_.bindForCompute();
  emitters.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  const GLuint outputOffset = bindLightRange(out, offset, count * size_t(bounces), LGH_BINDING_PASS1);
  const Bounds& b = scene_.scene().bounds;
  program.set("sampleCount", GLuint(total));
  program.set("firstSample", GLuint(first));
  program.set("batchCount", GLuint(count));
  program.set("maxBounces", GLuint(bounces));
  program.set("seed", GLuint(seed));
  program.set("outputOffset", outputOffset);
  program.set("sceneSphere", glm::vec4(b.center(), std::max(0.5f * b.diagonal(), 1e-6f)));
  program.dispatch1D(count, 64);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  gl::checkErrors("VPL generation");
}

size_t VplPass::compact(size_t slotCount, gl::Buffer& out, size_t offset) {
  gl::ensureSize(slotIndex_, {passes::kInputLights, "VPL slot index", "vpls"}, slotCount * sizeof(GLuint));
  pathSlots_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  slotIndex_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  compactFlags_.set("slotCount", GLuint(slotCount));
  compactFlags_.dispatch1D(slotCount, 256);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  const size_t written = prefixSum_.scan(slotIndex_, slotCount);
  if (written == 0) return 0;
  pathSlots_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  const GLuint outputOffset = bindLightRange(out, offset, written, LGH_BINDING_PASS1);
  slotIndex_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  compactWrite_.set("slotCount", GLuint(slotCount));
  compactWrite_.set("outputOffset", outputOffset);
  compactWrite_.dispatch1D(slotCount, 256);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  gl::checkErrors("VPL compaction");
  return written;
}

void VplPass::updateEmitters() {
  const bool geometry = emittersGeometryVersion_ != scene_.geometryVersion();
  if (emittersLightsVersion_ == scene_.lightsVersion() && !geometry) return;
  // A moved light keeps its power, but a changed intensity or cone changes every selection
  // probability, so the whole table is rebuilt (on a light edit or a moved scene, not per still frame;
  // cheap next to tracing the paths it feeds). Moved vertices move the emissive triangles.
  allEmitters_ = buildEmitterTable(scene_.scene(), scene_.lights());
  allEmitterBuffer_ = gl::Buffer::fromVector({passes::kInputLights, "emitters"}, allEmitters_.emitters, 0);
  if (geometry) {
    triangleEmitters_ = buildEmissiveTriangleTable(scene_.scene());
    triangleEmitterBuffer_ =
        gl::Buffer::fromVector({passes::kInputLights, "emissive triangles"}, triangleEmitters_.emitters, 0);
  }
  emittersLightsVersion_ = scene_.lightsVersion();
  emittersGeometryVersion_ = scene_.geometryVersion();
}

size_t VplPass::tracePaths(gl::Buffer& out, size_t offset, size_t budget, int bounces, std::uint32_t seed) {
  updateEmitters();
  const size_t paths = pathCount(budget, bounces), slots = maxVplCount(budget, bounces);
  if (bounces < 1 || allEmitters_.empty() || paths == 0) return 0;
  if (offset + slots > out.size() / sizeof(gpu::GpuLight))
    throw std::out_of_range("VplPass: the output buffer is too small");
  // In batches whose slots fit one storage block; the same VPLs as in one batch (each path draws from its own
  // index's random sequence, and compaction keeps path order).
  const size_t batch = batchSamples(bounces);
  size_t written = 0;
  for (size_t first = 0; first < paths; first += batch) {
    const size_t count = std::min(batch, paths - first);
    gl::ensureSize(pathSlots_, {passes::kInputLights, "VPL path slots", "vpls"},
                   count * size_t(bounces) * sizeof(gpu::GpuLight));
    pathSlots_.clear();  // flags 0: a slot no path wrote
    generate(paths_(scene_), allEmitterBuffer_, pathSlots_, 0, first, count, paths, bounces, seed);
    written += compact(count * size_t(bounces), out, offset + written);
  }
  // The paths' slots are generation scratch: the frame holds S0, not them.
  pathSlots_ = {};
  slotIndex_ = {};
  prefixSum_.release();
  return written;
}

size_t VplPass::sampleEmissiveTriangles(gl::Buffer& out, size_t offset, size_t count, std::uint32_t seed) {
  updateEmitters();
  if (triangleEmitters_.empty() || count == 0) return 0;
  const size_t batch = batchSamples(1);
  for (size_t first = 0; first < count; first += batch)
    generate(emitterSamples_(scene_), triangleEmitterBuffer_, out, offset + first, first,
             std::min(batch, count - first), count, 1, seed);
  return count;  // every sample writes its slot
}

}  // namespace lgh
