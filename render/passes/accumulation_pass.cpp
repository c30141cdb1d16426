#include "render/passes/accumulation_pass.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/accumulation_types.h"
#include "shared/bindings.h"

namespace lgh {

AccumulationPass::AccumulationPass()
    : program_(gl::Program::compute("accumulate.comp")),
      uniforms_(passes::kAccumulation, sizeof(gpu::AccumulationUniforms)) {}

void AccumulationPass::release() {
  history_[0] = {};
  history_[1] = {};
  rawRatios_ = {};
  hasHistory_ = false;
  uniforms_.release();
}

void AccumulationPass::execute(const AccumulationInputs& in, const AccumulationSettings& settings,
                               const AccumulationTargets& io) {
  if (settings.maxFrames < 1)
    throw std::invalid_argument("accumulation: at most " + std::to_string(settings.maxFrames) +
                                " frames (use 1 or more)");
  const GBuffer& gbuffer = in.gbuffer;
  History& previous = history_[current_];
  History& next = history_[1 - current_];
  for (History* h : {&previous, &next}) {
    if (h->irradianceSum.width() == gbuffer.width && h->irradianceSum.height() == gbuffer.height) continue;
    const int w = gbuffer.width, h2 = gbuffer.height;
    h->irradianceSum =
        gl::Texture2D({passes::kAccumulation, "history: irradiance sums", kImageSize}, w, h2, GL_RGBA32F);
    h->ratioSum = gl::Texture2D({passes::kAccumulation, "history: ratio sums", kImageSize}, w, h2, GL_RGBA32F);
    h->heaviest = gl::Texture2D({passes::kAccumulation, "history: heaviest frame", kImageSize}, w, h2, GL_RG32F);
    h->position = gl::Texture2D({passes::kAccumulation, "history: position", kImageSize}, w, h2, GL_RGBA32F);
    h->normal = gl::Texture2D({passes::kAccumulation, "history: normal", kImageSize}, w, h2, GL_RGBA16F);
    hasHistory_ = false;
  }
  // Stage 0 (sums and outputs), and with interleaving stage 1 (pixels whose sums lack some tiles: resolved
  // from the new sums, over a window that shrinks with N).
  gpu::AccumulationUniforms sums{};
  sums.previousViewProjection = previousView_.cameraRelativeViewProjection;
  sums.previousCameraPosition = previousView_.position;
  sums.maxFrames = float(settings.maxFrames);
  sums.stage = gpu::kAccumulateSums;
  sums.hasHistory = hasHistory_ ? 1u : 0u;
  sums.shadowSamples = unsigned(std::max(in.shadowSamples, 0));
  sums.tilesPerAxis = unsigned(in.layout.tilesPerAxis);
  sums.tileWidth = unsigned(in.layout.tileSize.x);
  sums.tileHeight = unsigned(in.layout.tileSize.y);
  sums.planeTolerance = kHistoryPlaneTolerance;
  sums.normalTolerance = kHistoryNormalTolerance;
  // What a frame in which the lights or the geometry moved does with the history (restart: nothing left).
  sums.motion = in.moved && hasHistory_ ? unsigned(settings.motion) + 1u : gpu::kMotionNone;
  sums.motionTolerance = std::max(settings.motionTolerance, 1e-6f);
  sums.irradianceWhole = in.wholeIrradiance ? 1u : 0u;
  gpu::AccumulationUniforms resolve = sums;
  const InterleaveFilter& filter = in.resolve;
  resolve.stage = gpu::kAccumulateResolveIncomplete;
  resolve.normalPower = filter.normalPower;
  resolve.planeSigma = std::max(filter.planeSigma, 1e-6f);
  uniforms_.upload(std::vector<gpu::AccumulationUniforms>{sums, resolve});

  gbuffer.bindForReading();
  in.rawIrradiance.bindTexture(LGH_TEXTURE_ACCUM_RAW_IRRADIANCE);
  previous.irradianceSum.bindTexture(LGH_TEXTURE_ACCUM_IRRADIANCE_SUM);
  previous.ratioSum.bindTexture(LGH_TEXTURE_ACCUM_RATIO_SUM);
  previous.heaviest.bindTexture(LGH_TEXTURE_ACCUM_HEAVIEST);
  // The history test under motion reads the raw ratios around each pixel, which the pass overwrites in place.
  if (sums.motion == gpu::kMotionGradient && in.shadowSamples > 0) {
    if (rawRatios_.width() != gbuffer.width || rawRatios_.height() != gbuffer.height)
      rawRatios_ = gl::Texture2D({passes::kAccumulation, "raw ratios under motion", kImageSize}, gbuffer.width,
                                 gbuffer.height, GL_RGBA32F);
    glCopyImageSubData(io.ratio.id(), GL_TEXTURE_2D, 0, 0, 0, 0, rawRatios_.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       gbuffer.width, gbuffer.height, 1);
    rawRatios_.bindTexture(LGH_TEXTURE_ACCUM_RAW_RATIO);
  }
  previous.position.bindTexture(LGH_TEXTURE_ACCUM_PREVIOUS_POSITION);
  previous.normal.bindTexture(LGH_TEXTURE_ACCUM_PREVIOUS_NORMAL);
  io.irradiance.bindImage(LGH_IMAGE_ACCUM_IRRADIANCE, GL_READ_WRITE);
  io.ratio.bindImage(LGH_IMAGE_ACCUM_RATIO, GL_READ_WRITE);
  io.sampledIrradiance.bindImage(LGH_IMAGE_ACCUM_SAMPLED_IRRADIANCE, GL_WRITE_ONLY);
  next.irradianceSum.bindImage(LGH_IMAGE_ACCUM_IRRADIANCE_SUM, GL_WRITE_ONLY);
  next.ratioSum.bindImage(LGH_IMAGE_ACCUM_RATIO_SUM, GL_WRITE_ONLY);
  next.heaviest.bindImage(LGH_IMAGE_ACCUM_HEAVIEST, GL_WRITE_ONLY);
  next.position.bindImage(LGH_IMAGE_ACCUM_POSITION, GL_WRITE_ONLY);
  next.normal.bindImage(LGH_IMAGE_ACCUM_NORMAL, GL_WRITE_ONLY);
  uniforms_.bind(0, LGH_UBO_PASS);
  program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  if (in.layout.tilesPerAxis > 1) {
    next.irradianceSum.bindTexture(LGH_TEXTURE_ACCUM_IRRADIANCE_SUM);
    uniforms_.bind(1, LGH_UBO_PASS);
    program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  gl::checkErrors("accumulation");
  current_ = 1 - current_;
  hasHistory_ = true;
  previousView_ = in.view;
}

}  // namespace lgh
