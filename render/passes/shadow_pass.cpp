#include "render/passes/shadow_pass.h"

#include <utility>

#include "render/gl/debug.h"
#include "shared/bindings.h"

namespace lgh {

ShadowRayPass::ShadowRayPass() : program_(gl::Program::compute("shadow_rays.comp")) {}

void ShadowRayPass::execute(const SceneGpu& scene, const GBuffer& gbuffer, const ShadowSlots& slots,
                            const TileLayout& layout, const gl::Buffer& inputLights, const GpuHierarchy& hierarchy,
                            const ShadowTargets& targets, const LightPassOptions& lightPass,
                            const gl::Texture2D& lightPassIrradiance, gl::Texture2D& rawRatio) const {
  scene.bindForCompute();
  gbuffer.bindForReading();
  inputLights.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  slots.totals.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  slots.slots.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  slots.unselectable.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS5);
  lightPassIrradiance.bindTexture(LGH_TEXTURE_SHADOW_IRRADIANCE);
  // A buffer must be bound even when there is no hierarchy (brute force): the input lights stand in.
  (hierarchy.gridLights ? hierarchy.gridLights : inputLights).bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  const bool drawnTargets = targets.races > 0 && targets.targets;
  (drawnTargets ? targets.targets : inputLights).bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  rawRatio.bindImage(LGH_IMAGE_SHADOW_RATIO, GL_WRITE_ONLY);
  program_.set("samples", unsigned(slots.k));
  program_.set("tilesPerAxis", unsigned(layout.tilesPerAxis));
  program_.set("tileSize", glm::uvec2(layout.tileSize));
  program_.set("races", drawnTargets ? targets.races : 0u);
  program_.set("resampleTargets", int(lightPass.shadows.resampleTargets));
  program_.set("weighTargets", int(lightPass.shadows.weighTargets));
  program_.set("blendTargets", int(lightPass.shadows.blendTargets));
  program_.set("spread", lightPass.shadows.spread);
  program_.set("uniformSelection", int(lightPass.shadows.uniformSelection));
  program_.set("everyLevelSelected", int(!lightPass.shadows.skipFinest));
  program_.set("defensive", lightPass.shadows.defensive);
  program_.set("sampleSpread", lightPass.shadows.correctionSampleSpread);
  program_.set("clampDistance", lightPass.clampDistance);
  program_.set("alpha", lightPass.pass.alpha);
  program_.set("topCellSize", float(hierarchy.grid.topCellSize));
  program_.set("firstLevel", unsigned(lightPass.pass.startLevel));
  program_.set("levels", unsigned(std::max(hierarchy.grid.levels, 0)));
  program_.set("bruteForce", int(lightPass.pass.bruteForce));
  program_.set("frameSeed", lightPass.frameSeed);
  program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl::checkErrors("shadow rays");
}

ShadowFilterPass::ShadowFilterPass() : program_(gl::Program::compute("atrous.comp")) {}

void ShadowFilterPass::execute(const GBuffer& gbuffer, const gl::Texture2D& rawRatio, const gl::Texture2D& irradiance,
                               const ShadowFilterSettings& options, const IrradianceCorrection& correction,
                               gl::Texture2D& filteredRatio, float sigmaFade) {
  if (ping_.width() != gbuffer.width || ping_.height() != gbuffer.height) {
    ping_ = gl::Texture2D(gbuffer.width, gbuffer.height, GL_RGBA32F);
    pong_ = gl::Texture2D(gbuffer.width, gbuffer.height, GL_RGBA32F);
  }
  gbuffer.bindForReading();
  program_.set("normalPower", options.normalPower);
  program_.set("planeSigma", std::max(options.planeSigma, 1e-6f));
  program_.set("ratioSigma", std::max(options.ratioSigma, 1e-6f));
  program_.set("sigmaFade", sigmaFade);
  program_.set("passes", options.passes);
  program_.set("correctIrradiance", int(correction.enabled));
  program_.set("lghError", correction.lghError);
  auto run = [&](int stage, const gl::Texture2D& in, const gl::Texture2D& second, gl::Texture2D& out, int step) {
    in.bindTexture(LGH_TEXTURE_FILTER_SIGNAL);
    second.bindTexture(LGH_TEXTURE_FILTER_SECOND);
    out.bindImage(LGH_IMAGE_FILTER_OUT, GL_WRITE_ONLY);
    program_.set("stage", stage);
    program_.set("stepSize", step);
    program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  };
  run(0, rawRatio, irradiance, ping_, 1);
  gl::Texture2D* in = &ping_;
  gl::Texture2D* out = &pong_;
  for (int i = 0; i < options.passes; ++i) {
    run(1, *in, rawRatio, *out, 1 << i);
    std::swap(in, out);
  }
  run(2, *in, rawRatio, filteredRatio, 1);
  gl::checkErrors("shadow filter");
}

}  // namespace lgh
