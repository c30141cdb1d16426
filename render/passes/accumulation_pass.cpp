#include "render/passes/accumulation_pass.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "shared/bindings.h"

namespace lgh {

AccumulationPass::AccumulationPass() : program_(gl::Program::compute("accumulate.comp")) {}

void AccumulationPass::execute(const GBuffer& gbuffer, const CameraView& view, const gl::Texture2D& rawIrradiance,
                               const TileLayout& layout, bool shadowed, const AccumulationSettings& settings,
                               gl::Texture2D& irradiance, gl::Texture2D& ratio) {
  if (settings.maxFrames < 1)
    throw std::invalid_argument("accumulation: at most " + std::to_string(settings.maxFrames) +
                                " frames (use 1 or more)");
  History& previous = history_[current_];
  History& next = history_[1 - current_];
  for (History* h : {&previous, &next}) {
    if (h->irradianceSum.width() == gbuffer.width && h->irradianceSum.height() == gbuffer.height) continue;
    h->irradianceSum = gl::Texture2D(gbuffer.width, gbuffer.height, GL_RGBA32F);
    h->ratioSum = gl::Texture2D(gbuffer.width, gbuffer.height, GL_RGBA32F);
    h->position = gl::Texture2D(gbuffer.width, gbuffer.height, GL_RGBA32F);
    h->normal = gl::Texture2D(gbuffer.width, gbuffer.height, GL_RGBA16F);
    hasHistory_ = false;
  }
  gbuffer.bindForReading();
  rawIrradiance.bindTexture(LGH_TEXTURE_ACCUM_RAW_IRRADIANCE);
  previous.irradianceSum.bindTexture(LGH_TEXTURE_ACCUM_IRRADIANCE_SUM);
  previous.ratioSum.bindTexture(LGH_TEXTURE_ACCUM_RATIO_SUM);
  previous.position.bindTexture(LGH_TEXTURE_ACCUM_PREVIOUS_POSITION);
  previous.normal.bindTexture(LGH_TEXTURE_ACCUM_PREVIOUS_NORMAL);
  irradiance.bindImage(LGH_IMAGE_ACCUM_IRRADIANCE, GL_READ_WRITE);
  ratio.bindImage(LGH_IMAGE_ACCUM_RATIO, GL_READ_WRITE);
  next.irradianceSum.bindImage(LGH_IMAGE_ACCUM_IRRADIANCE_SUM, GL_WRITE_ONLY);
  next.ratioSum.bindImage(LGH_IMAGE_ACCUM_RATIO_SUM, GL_WRITE_ONLY);
  next.position.bindImage(LGH_IMAGE_ACCUM_POSITION, GL_WRITE_ONLY);
  next.normal.bindImage(LGH_IMAGE_ACCUM_NORMAL, GL_WRITE_ONLY);
  program_.set("hasHistory", int(hasHistory_));
  program_.set("shadowed", int(shadowed));
  program_.set("previousViewProjection", previousView_.cameraRelativeViewProjection);
  program_.set("previousCameraPosition", previousView_.position);
  program_.set("tilesPerAxis", unsigned(layout.tilesPerAxis));
  program_.set("tileSize", glm::uvec2(layout.tileSize));
  program_.set("maxFrames", float(settings.maxFrames));
  program_.set("planeTolerance", kHistoryPlaneTolerance);
  program_.set("normalTolerance", kHistoryNormalTolerance);
  program_.set("stage", 0);
  program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  if (layout.tilesPerAxis > 1) {
    // Pixels whose sums lack some tiles: resolved from the new sums, over a window that shrinks with N.
    const InterleaveFilter filter;
    next.irradianceSum.bindTexture(LGH_TEXTURE_ACCUM_IRRADIANCE_SUM);
    program_.set("stage", 1);
    program_.set("normalPower", filter.normalPower);
    program_.set("planeSigma", std::max(filter.planeSigma, 1e-6f));
    program_.dispatch2D(gbuffer.width, gbuffer.height, {8, 8});
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  }
  gl::checkErrors("accumulation");
  current_ = 1 - current_;
  hasHistory_ = true;
  previousView_ = view;
}

}  // namespace lgh
