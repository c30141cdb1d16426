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
  const RtslcSettings& lightcuts = options.lightcuts;
  const int passes = std::max(options.passes, 0);
  if (passes > 0 && (ping_.width() != gbuffer.width || ping_.height() != gbuffer.height)) {
    ping_ = gl::Texture2D({passes::kIrradianceFilter, "ping", kImageSize}, gbuffer.width, gbuffer.height, GL_RGBA32F);
    pong_ = gl::Texture2D({passes::kIrradianceFilter, "pong", kImageSize}, gbuffer.width, gbuffer.height, GL_RGBA32F);
  }
  // Dispatch 0 resolves and estimates the variance; dispatch i > 0 is the a-trous pass with holes 2^(i-1).
  std::vector<gpu::IrradianceFilterUniforms> dispatches(size_t(passes) + 1);
  for (int i = 0; i <= passes; ++i) {
    gpu::IrradianceFilterUniforms& u = dispatches[size_t(i)];
    u.stage = i == 0 ? gpu::kIrradianceVariance : gpu::kIrradiancePass;
    u.stepSize = i == 0 ? 1 : 1 << (i - 1);
    u.passes = passes;
    u.interleave = unsigned(std::max(lightcuts.interleave, 1));
    u.normalPower = lightcuts.filterNormalPower;
    u.planeSigma = std::max(lightcuts.filterPlaneSigma, 1e-6f);
    u.luminanceSigma = std::max(lightcuts.filterSigma, 1e-6f);
    u.sigmaFade = options.sigmaFade;
    u.hasMoments = options.moments ? 1u : 0u;
    u.minTemporal = kMinTemporalFrames;
  }
  uniforms_.upload(dispatches);
  gbuffer.bindForReading();
  if (options.moments) options.moments->bindTexture(LGH_TEXTURE_FILTER_SECOND);
  // Each dispatch reads the last one's output; the last writes `filtered`.
  const gl::Texture2D* signal = &irradiance;
  gl::Texture2D* out = &ping_;
  for (int i = 0; i <= passes; ++i) {
    if (i == passes) out = &filtered;
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
