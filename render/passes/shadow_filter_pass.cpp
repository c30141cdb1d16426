#include "render/passes/shadow_filter_pass.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/shadow_filter_types.h"

namespace lgh {

ShadowFilterPass::ShadowFilterPass()
    : program_(gl::Program::compute("atrous.comp")),
      uniforms_(passes::kShadowFilter, sizeof(gpu::ShadowFilterUniforms)) {}

void ShadowFilterPass::release() {
  ping_ = {};
  pong_ = {};
  uniforms_.release();
}

void ShadowFilterPass::execute(const ShadowFilterInputs& in, const ShadowFilterOptions& options,
                               gl::Texture2D& visibility) {
  const GBuffer& gbuffer = in.gbuffer;
  if (ping_.width() != gbuffer.width || ping_.height() != gbuffer.height) {
    ping_ = gl::Texture2D({passes::kShadowFilter, "ping", kImageSize}, gbuffer.width, gbuffer.height, GL_RGBA32F);
    pong_ = gl::Texture2D({passes::kShadowFilter, "pong", kImageSize}, gbuffer.width, gbuffer.height, GL_RGBA32F);
  }
  // The dispatches: prepare, resolve (interleaving), one pass per step 1, 2, ..., 2^(passes - 1), finish.
  const ShadowFilterSettings& filter = options.filter;
  gpu::ShadowFilterUniforms common{};
  common.passes = filter.passes;
  common.correctIrradiance = options.correction.enabled ? 1u : 0u;
  common.normalPower = filter.normalPower;
  common.planeSigma = std::max(filter.planeSigma, 1e-6f);
  common.ratioSigma = std::max(filter.ratioSigma, 1e-6f);
  common.sigmaFade = options.sigmaFade;
  common.lghError = options.correction.lghError;
  common.tilesPerAxis = unsigned(std::max(options.tilesPerAxis, 1));
  std::vector<gpu::ShadowFilterUniforms> dispatches;
  auto add = [&](unsigned stage, int step) {
    dispatches.push_back(common);
    dispatches.back().stage = stage;
    dispatches.back().stepSize = step;
  };
  add(gpu::kFilterPrepare, 1);
  if (common.tilesPerAxis > 1) {
    add(gpu::kFilterResolve, 1);
    dispatches.back().normalPower = options.resolve.normalPower;
    dispatches.back().planeSigma = std::max(options.resolve.planeSigma, 1e-6f);
  }
  for (int i = 0; i < filter.passes; ++i) add(gpu::kFilterPass, 1 << i);
  add(gpu::kFilterFinish, 1);
  uniforms_.upload(dispatches);

  gbuffer.bindForReading();
  auto run = [&](size_t dispatch, const gl::Texture2D& signal, const gl::Texture2D& second, gl::Texture2D& out) {
    signal.bindTexture(LGH_TEXTURE_FILTER_SIGNAL);
    second.bindTexture(LGH_TEXTURE_FILTER_SECOND);
    out.bindImage(LGH_IMAGE_FILTER_OUT, GL_WRITE_ONLY);
    uniforms_.bind(dispatch, LGH_UBO_PASS);
    program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  };
  run(0, in.rawRatio, in.sampledIrradiance, ping_);
  gl::Texture2D* signal = &ping_;
  gl::Texture2D* out = &pong_;
  for (size_t i = 1; i + 1 < dispatches.size(); ++i) {  // resolve and a-trous passes
    run(i, *signal, in.rawRatio, *out);
    std::swap(signal, out);
  }
  run(dispatches.size() - 1, *signal, in.rawRatio, visibility);
  gl::checkErrors("shadow filter");
}

}  // namespace lgh
