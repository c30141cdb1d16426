#include "render/passes/shadow_ray_pass.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/bvh_types.h"
#include "shared/shadow_ray_types.h"

namespace lgh {

ShadowRayPass::ShadowRayPass()
    : sampling_(gl::Program::compute("shadow_rays.comp")),
      recording_(gl::Program::compute("shadow_rays.comp", {{"LGH_SHADOW_RAYS_RECORD", "1"}})),
      trace_("shadow_trace.comp"),
      ratio_(gl::Program::compute("shadow_ratio.comp")),
      queueTexels_(GL_RGBA32UI),
      inputLightTexels_(GL_RGBA32UI),
      uniforms_(passes::kShadowRays, sizeof(gpu::ShadowRayUniforms)) {}

void ShadowRayPass::release() {
  queue_ = {};
  slotWeights_ = {};
  uniforms_.release();
}

void ShadowRayPass::execute(const ShadowRayInputs& in, const ShadowRayOptions& options, const ShadowRayTargets& out) {
  const bool drawnTargets = in.targets.races > 0 && in.targets.targets;
  gpu::ShadowRayUniforms u{};
  u.samples = unsigned(in.slots.k);
  u.tilesPerAxis = unsigned(in.layout.tilesPerAxis);
  u.tileWidth = unsigned(in.layout.tileSize.x);
  u.tileHeight = unsigned(in.layout.tileSize.y);
  u.races = drawnTargets ? in.targets.races : 0u;
  u.selectFlags = selectionFlags(options.shadows);
  u.resampleTargets = options.shadows.resampleTargets ? 1u : 0u;
  u.weighTargets = options.shadows.weighTargets ? 1u : 0u;
  u.spread = options.shadows.spread;
  u.defensive = options.shadows.defensive;
  u.sampleSpread = options.shadows.correctionSampleSpread;
  u.clampDistance = options.clampDistance;
  u.alpha = options.alpha;
  u.topCellSize = float(in.hierarchy.grid.topCellSize);
  u.firstLevel = unsigned(options.startLevel);
  u.levels = unsigned(std::max(in.hierarchy.grid.levels, 0));
  u.bruteForce = options.bruteForce ? 1u : 0u;
  u.frameSeed = options.frameSeed;
  // The rows whose rays the queue holds at once (every slot may need a ray), queued and traced in turn.
  const size_t width = size_t(in.gbuffer.width), height = size_t(in.gbuffer.height), k = size_t(in.slots.k);
  if (width == 0 || height == 0) return;
  const size_t rowRays = std::max<size_t>(width * k, 1);
  const size_t rowsPerBatch = std::clamp<size_t>(options.queuedRays / rowRays, 1, height);
  std::vector<gpu::ShadowRayUniforms> batches;
  for (size_t row = 0; row < height; row += rowsPerBatch) {
    u.firstRow = unsigned(row);
    u.endRow = unsigned(std::min(height, row + rowsPerBatch));
    batches.push_back(u);
  }
  uniforms_.upload(batches);
  const size_t capacity = rowsPerBatch * rowRays;
  if (capacity > size_t(65535) * gpu::kShadowTraceGroupSize)
    throw std::invalid_argument("ShadowRayPass: a row's rays (width x k) overflow one dispatch of the trace");
  gl::fitSize(queue_, {passes::kShadowRays, "queued rays", "width x min(height, shadow-queued-rays / (width x k))"},
              sizeof(gpu::ShadowRayQueueCounts) + capacity * sizeof(gpu::QueuedShadowRay));
  gl::fitSize(slotWeights_, {passes::kShadowRays, "slot weights", "width x height x shadow-samples"},
              std::max<size_t>(width * height * k, 1) * sizeof(float));
  queueTexels_.attach(queue_);
  queueTexels_.bindTexture(LGH_TEXTURE_SHADOW_QUEUE);
  queueTexels_.bindImage(LGH_IMAGE_SHADOW_QUEUE, GL_WRITE_ONLY);

  in.gbuffer.bindForReading();
  inputLightTexels_.attach(in.inputLights, in.inputLightCount * sizeof(gpu::GpuLight));
  inputLightTexels_.bindTexture(LGH_TEXTURE_SHADOW_INPUT_LIGHTS);
  in.slots.totals.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  in.slots.slots.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  in.slots.unselectable.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS5);
  in.lightPassIrradiance.bindTexture(LGH_TEXTURE_SHADOW_IRRADIANCE);
  // A buffer must be bound even when there is no hierarchy (brute force): the input lights stand in.
  (in.hierarchy.gridLights ? in.hierarchy.gridLights : in.inputLights)
      .bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  (drawnTargets ? in.targets.targets : in.inputLights).bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  queue_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  slotWeights_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS7);
  out.rawRatio.bindImage(LGH_IMAGE_SHADOW_RATIO, GL_READ_WRITE);
  out.sampledIrradiance.bindImage(LGH_IMAGE_SHADOW_SAMPLED_IRRADIANCE, GL_WRITE_ONLY);
  const gl::Program* sampling = &sampling_;
  if (out.recordedRays) {
    if (out.recordedRays->size() < width * height * k * sizeof(gpu::GpuRay))
      throw std::invalid_argument("ShadowRayPass: the buffer recording the rays holds fewer than W x H x k");
    out.recordedRays->clear();
    out.recordedRays->bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS6);
    sampling = &recording_;
  }
  const gl::Program& trace = trace_(in.scene);
  in.scene.bindForCompute();
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, queue_.id());
  const gpu::ShadowRayQueueCounts empty{0u, 0u, 1u, 1u};
  for (size_t b = 0; b < batches.size(); ++b) {
    queue_.update(&empty, sizeof(empty));
    uniforms_.bind(b, LGH_UBO_PASS);
    sampling->dispatch2D(int(width), int(batches[b].endRow - batches[b].firstRow), {8, 8});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    if (!options.trace) continue;
    trace.use();
    glDispatchComputeIndirect(GLintptr(gpu::kShadowQueueDispatchOffset));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  uniforms_.bind(0, LGH_UBO_PASS);
  ratio_.dispatch2D(int(width), int(height), {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl::checkErrors("shadow rays");
}

}  // namespace lgh
