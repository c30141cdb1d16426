#include "render/passes/irradiance_filter_pass.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/irradiance_filter_types.h"

namespace lgh {

IrradianceFilterPass::IrradianceFilterPass()
    : program_(gl::Program::compute("irradiance_atrous.comp")),
      uniforms_(passes::kIrradianceFilter, sizeof(gpu::IrradianceFilterUniforms)) {}

void IrradianceFilterPass::release() {
  ping_ = {};
  pong_ = {};
  uniforms_.release();
}

void IrradianceFilterPass::execute(const GBuffer& gbuffer, const gl::Texture2D& irradiance,
                                   const IrradianceFilterOptions& options, gl::Texture2D& filtered) {
  const ShadowFilterSettings& filter = options.filter;
  if (filter.passes <= 0) {
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // the copy reads what image stores wrote
    glCopyImageSubData(irradiance.id(), GL_TEXTURE_2D, 0, 0, 0, 0, filtered.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       gbuffer.width, gbuffer.height, 1);
    gl::checkErrors("irradiance filter (copy)");
    return;
  }
  if (ping_.width() != gbuffer.width || ping_.height() != gbuffer.height) {
    ping_ = gl::Texture2D({passes::kIrradianceFilter, "ping", kImageSize}, gbuffer.width, gbuffer.height, GL_RGBA32F);
    pong_ = gl::Texture2D({passes::kIrradianceFilter, "pong", kImageSize}, gbuffer.width, gbuffer.height, GL_RGBA32F);
  }
  std::vector<gpu::IrradianceFilterUniforms> passes(size_t(filter.passes));
  for (int i = 0; i < filter.passes; ++i) {
    gpu::IrradianceFilterUniforms& u = passes[size_t(i)];
    u.stepSize = 1 << i;
    u.passes = filter.passes;
    u.normalPower = filter.normalPower;
    u.planeSigma = std::max(filter.planeSigma, 1e-6f);
    u.luminanceSigma = std::max(filter.ratioSigma, 1e-6f);
    u.sigmaFade = options.sigmaFade;
    u.frames = float(std::max(options.frames, 1));
  }
  uniforms_.upload(passes);
  gbuffer.bindForReading();
  // Pass i reads the last pass's output; the last pass writes `filtered`.
  const gl::Texture2D* signal = &irradiance;
  gl::Texture2D* out = &ping_;
  for (int i = 0; i < filter.passes; ++i) {
    if (i + 1 == filter.passes) out = &filtered;
    signal->bindTexture(LGH_TEXTURE_FILTER_SIGNAL);
    out->bindImage(LGH_IMAGE_FILTER_OUT, GL_WRITE_ONLY);
    uniforms_.bind(size_t(i), LGH_UBO_PASS);
    program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    signal = out;
    out = out == &ping_ ? &pong_ : &ping_;
  }
  gl::checkErrors("irradiance filter");
}

}  // namespace lgh
