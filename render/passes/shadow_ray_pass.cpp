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
    : program_("shadow_rays.comp"),
      untraced_("shadow_rays.comp", {{"LGH_SHADOW_RAYS_UNTRACED", "1"}}),
      recording_("shadow_rays.comp", {{"LGH_SHADOW_RAYS_RECORD", "1"}}),
      lightFloats_(GL_RGBA32F),
      lightWords_(GL_RGBA32UI),
      uniforms_(passes::kShadowRays, sizeof(gpu::ShadowRayUniforms)) {}

void ShadowRayPass::release() { uniforms_.release(); }

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
  uniforms_.upload(std::vector<gpu::ShadowRayUniforms>{u});

  in.scene.bindForCompute();
  in.gbuffer.bindForReading();
  lightFloats_.attach(in.inputLights, in.inputLightCount * sizeof(gpu::GpuLight));
  lightWords_.attach(in.inputLights, in.inputLightCount * sizeof(gpu::GpuLight));
  lightFloats_.bindTexture(LGH_TEXTURE_SHADOW_LIGHT_FLOATS);
  lightWords_.bindTexture(LGH_TEXTURE_SHADOW_LIGHT_WORDS);
  in.slots.totals.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  in.slots.slots.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  in.slots.unselectable.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS5);
  in.lightPassIrradiance.bindTexture(LGH_TEXTURE_SHADOW_IRRADIANCE);
  // A buffer must be bound even when there is no hierarchy (brute force): the input lights stand in.
  (in.hierarchy.gridLights ? in.hierarchy.gridLights : in.inputLights)
      .bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  (drawnTargets ? in.targets.targets : in.inputLights).bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  out.rawRatio.bindImage(LGH_IMAGE_SHADOW_RATIO, GL_WRITE_ONLY);
  out.sampledIrradiance.bindImage(LGH_IMAGE_SHADOW_SAMPLED_IRRADIANCE, GL_WRITE_ONLY);
  uniforms_.bind(0, LGH_UBO_PASS);
  TracingProgram* program = &program_;
  if (out.recordedRays) {
    const size_t rays = size_t(in.gbuffer.width) * size_t(in.gbuffer.height) * size_t(in.slots.k);
    if (out.recordedRays->size() < rays * sizeof(gpu::GpuRay))
      throw std::invalid_argument("ShadowRayPass: the buffer recording the rays holds fewer than W x H x k");
    out.recordedRays->clear();
    out.recordedRays->bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS6);
    program = &recording_;
  }
  if (!options.trace) program = &untraced_;
  (*program)(in.scene).dispatch2D(in.gbuffer.width, in.gbuffer.height, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl::checkErrors("shadow rays");
}

}  // namespace lgh
