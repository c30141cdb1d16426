#include "render/indirect/rtslc_indirect.h"

#include "render/pass_names.h"

namespace lgh {

void RtslcIndirect::freeTargets() {
  for (gl::Texture2D* t : {&irradiance_, &filtered_, &moments_, &sampledIrradiance_, &unshadowed_, &ratio_,
                           &sampledLuminance_, &visibility_})
    *t = {};
}

void RtslcIndirect::allocate(const RenderSettings& settings) {
  allocated_ = settings;
  const int w = settings.image.width, h = settings.image.height;
  auto make = [&](const char* owner, const char* name, GLenum format) {
    return gl::Texture2D({owner, name, kImageSize}, w, h, format);
  };
  freeTargets();
  irradiance_ = make(passes::kLightcutSampling, "irradiance", GL_RGBA32F);
  if (ratioForm()) {
    unshadowed_ = make(passes::kLightcutSampling, "unshadowed irradiance", GL_RGBA32F);
    ratio_ = make(passes::kLightcutSampling, "raw ratio", GL_RGBA32F);
    sampledLuminance_ = make(passes::kLightcutSampling, "unshadowed luminance", GL_R32F);
    visibility_ = make(passes::kShadowFilter, "visibility", GL_RGBA32F);
  }
  filtered_ = make(passes::kIrradianceFilter, "filtered irradiance", GL_RGBA32F);
  if (settings.accumulation.enabled) {
    moments_ = make(passes::kAccumulation, "ratio", GL_RGBA32F);
    moments_.clear(glm::vec4(1.0f));
    sampledIrradiance_ = make(passes::kAccumulation, "sampled irradiance", GL_R32F);
    sampledIrradiance_.clear(glm::vec4(0.0f));
  }
}

void RtslcIndirect::release(LightBuilds& builds) {
  freeTargets();
  lightTree_ = {};
  builds.freedLightTree();
  rtslcPass_.release();
  filterPass_.release();
  ratioFilterPass_.release();
}

bool RtslcIndirect::updateStructure(const IndirectFrame& frame, const InputLightKey& lights, LightBuilds& builds) {
  if (!builds.plan(lights, frame.settings.hierarchy.levels, false, true).lightTree) return false;
  frame.timed(passes::kLightTreeBuild,
              [&] { lightTreePass_.execute(frame.lights.lights, frame.lights.count, lightTree_); });
  builds.builtLightTree();
  return true;
}

LightStats RtslcIndirect::estimate(const IndirectFrame& frame) {
  // A cut of the light tree per pixel block, one light drawn under each cut node per pixel with its shadow
  // ray: the shadowed irradiance, unbiased.
  const RtslcInputs in{frame.scene, frame.gbuffer, frame.lights.lights, frame.lights.count, lightTree_};
  RtslcOptions options;
  options.settings = frame.settings.rtslc;
  options.clampDistance = frame.clampDistance;
  options.frameSeed = frame.frameSeed();
  frame.timed(passes::kLightcutCuts, [&] { rtslcPass_.selectCuts(in, options); });
  frame.timed(passes::kLightcutSampling, [&] {
    if (ratioForm())
      rtslcPass_.sample(in, options, {irradiance_, &unshadowed_, &ratio_, &sampledLuminance_});
    else
      rtslcPass_.sample(in, options, {irradiance_});
  });
  return {};
}

AccumulationSource RtslcIndirect::accumulation(const IndirectFrame& frame) {
  // The ratio form's sums are accumulated as the LGH's are: the unshadowed irradiance, and the ratio with
  // its weight.
  if (ratioForm())
    return {unshadowed_,
            TileLayout::of(1, allocated_.image.width, allocated_.image.height),
            frame.settings.rtslc.samples,
            {unshadowed_, ratio_, sampledLuminance_}};
  // Each frame is unbiased (with m x m interleaving, every m^2 frames are): summed as it is, the luminance's
  // moments beside it for the filter.
  return {irradiance_,
          TileLayout::of(1, allocated_.image.width, allocated_.image.height),
          0,
          {irradiance_, moments_, sampledIrradiance_}};
}

IndirectImage RtslcIndirect::filter(const IndirectFrame& frame) {
  if (ratioForm()) {
    const float fade = frame.accumulating ? frame.settings.accumulation.filterFade : 0.0f;
    frame.timed(passes::kIrradianceFilter, [&] {
      filterPass_.execute(frame.gbuffer, unshadowed_, {frame.settings.filter.passes, frame.settings.rtslc, fade},
                          filtered_);
    });
    frame.timed(passes::kShadowFilter, [&] {
      ShadowFilterOptions o;
      o.filter = frame.settings.filter;
      o.sigmaFade = fade;
      o.tilesPerAxis = frame.settings.rtslc.interleave;
      ratioFilterPass_.execute({frame.gbuffer, ratio_, sampledLuminance_}, o, visibility_);
    });
    return {&filtered_, &visibility_};
  }
  frame.timed(passes::kIrradianceFilter, [&] {
    const bool moments = frame.accumulating;
    filterPass_.execute(frame.gbuffer, irradiance_,
                        {frame.settings.filter.passes, frame.settings.rtslc,
                         moments ? frame.settings.accumulation.filterFade : 0.0f, moments ? &moments_ : nullptr},
                        filtered_);
  });
  return {&filtered_, nullptr};
}

const gl::Texture2D* RtslcIndirect::target(Aov aov) const {
  // The irradiance is filtered as the composite uses it: shadowed, or in ratio form unshadowed, with the
  // raw and the filtered visibility ratio beside it. The LGH's overdraw has no counterpart here.
  switch (aov) {
    case Aov::Irradiance:
      return &filtered_;
    case Aov::Ratio:
      return ratioForm() ? &ratio_ : nullptr;
    case Aov::Visibility:
      return ratioForm() ? &visibility_ : nullptr;
    case Aov::History:  // the frames in alpha: the ratio's in ratio form, the moments' otherwise
      return ratioForm() ? &ratio_ : &moments_;
    default:
      return nullptr;
  }
}

}  // namespace lgh
