#include "render/indirect/lgh_indirect.h"

#include <cstdio>

#include "render/pass_names.h"

namespace lgh {

LghIndirect::LghIndirect(bool floatAtomics) : buildPass_(floatAtomics), lightPass_(floatAtomics) {}

LghBuildOptions LghIndirect::buildOptions(const SceneGpu& scene, const RenderSettings& settings) {
  LghBuildOptions o;
  o.levels = settings.hierarchy.levels;
  o.eMin = minTopCellFor(scene.scene().bounds.diagonal());
  return o;
}

void LghIndirect::allocate(const RenderSettings& settings) {
  allocated_ = settings;
  const int w = settings.image.width, h = settings.image.height;
  auto make = [&](const char* owner, const char* name, GLenum format) {
    return gl::Texture2D({owner, name, kImageSize}, w, h, format);
  };
  // The old set goes before the new is allocated: a switch holds one set at a time.
  freeTargets();
  if (!shadowed()) releaseShadowSampling();
  const bool overdraw = settings.lightPass.overdraw, accumulating = settings.accumulation.enabled;
  if (interleaved()) tiles_ = Tiles(TileLayout::of(settings.lightPass.interleave, w, h), overdraw);
  irradiance_ = make(passes::kLightPass, "irradiance", GL_RGBA32F);
  if (overdraw) {
    fragmentCounts_ = make(passes::kLightPass, "fragment counts", GL_R32UI);
    fragmentCounts_.clearUint(0);
  }
  // The raw ratio and the sampled irradiance: the shadow rays' outputs, and the accumulation's (unshadowed:
  // the luminance's moments).
  if (shadowed() || accumulating) {
    const char* owner = shadowed() ? passes::kShadowRays : passes::kAccumulation;
    rawRatio_ = make(owner, "ratio", GL_RGBA32F);
    rawRatio_.clear(glm::vec4(1.0f));
    sampledIrradiance_ = make(owner, "sampled irradiance", GL_R32F);
    sampledIrradiance_.clear(glm::vec4(0.0f));
  }
  if (shadowed()) visibility_ = make(passes::kShadowFilter, "visibility", GL_RGBA32F);
}

void LghIndirect::freeTargets() {
  tiles_ = {};
  for (gl::Texture2D* t : {&irradiance_, &fragmentCounts_, &rawRatio_, &sampledIrradiance_, &visibility_}) *t = {};
}

void LghIndirect::releaseShadowSampling() {
  shadowSlots_ = {};
  shadowTargets_ = {};
  shadowTargetsPass_.release();
  shadowRayPass_.release();
  shadowFilterPass_.release();
}

void LghIndirect::release(LightBuilds& builds) {
  freeTargets();
  releaseShadowSampling();
  lightPass_.release();
  hierarchy_ = {};
  builds.freedHierarchy();
}

bool LghIndirect::updateStructure(const IndirectFrame& frame, const InputLightKey& lights, LightBuilds& builds) {
  const LghBuildOptions options = buildOptions(frame.scene, frame.settings);
  // Brute force draws every input light: no hierarchy is held.
  if (frame.settings.lightPass.bruteForce) {
    hierarchy_ = {};
    builds.freedHierarchy();
    return false;
  }
  if (!builds.plan(lights, options.levels, true).hierarchy) return false;
  frame.timed(passes::kLghBuild,
              [&] { buildPass_.execute(frame.lights.lights, frame.lights.count, options, hierarchy_); });
  builds.builtHierarchy(options.levels);
  return true;
}

void LghIndirect::resolveShadows(const IndirectFrame& frame) {
  ShadowEstimatorLimits limits;
  limits.bruteForce = frame.settings.lightPass.bruteForce;
  limits.inputLights = frame.lights.count;
  limits.inputLightsPerBlock = lightPass_.inputLightsPerBlock();
  ResolvedShadowEstimator resolved = resolveShadowEstimator(frame.settings.shadows, limits);
  for (const std::string& line : resolved.switchedOff)
    if (reportedLimits_.insert(line).second) std::fprintf(stderr, "lgh: %s\n", line.c_str());
  shadowEstimator_ = resolved.estimator;
}

LightPassOptions LghIndirect::lightPassOptions(const IndirectFrame& frame) const {
  LightPassOptions o;
  o.pass = frame.settings.lightPass;
  o.shadows = shadowEstimator_;
  o.clampDistance = frame.clampDistance;
  o.sceneSize = std::max(frame.scene.scene().bounds.diagonal(), 1e-6f);
  o.frameSeed = frame.frameSeed();
  // Accumulating, consecutive frames deal the lights to the n x n tiles shifted by one more, so any n^2
  // of them give every pixel every light exactly once (without, frame after frame the same dealing).
  o.tileRotation = frame.accumulating ? frame.frameIndex : 0u;
  return o;
}

ShadowRayOptions LghIndirect::shadowRayOptions(const IndirectFrame& frame, const LightPassOptions& lightPass) {
  ShadowRayOptions o;
  o.shadows = lightPass.shadows;
  o.trace = frame.settings.shadows.trace;
  o.queuedRays = size_t(frame.settings.shadows.queuedRays);
  o.alpha = lightPass.pass.alpha;
  o.startLevel = lightPass.pass.startLevel;
  o.bruteForce = lightPass.pass.bruteForce;
  o.clampDistance = lightPass.clampDistance;
  o.frameSeed = lightPass.frameSeed;
  return o;
}

ShadowFilterOptions LghIndirect::shadowFilterOptions(const IndirectFrame& frame) const {
  ShadowFilterOptions o;
  o.filter = frame.settings.filter;
  o.correction = {shadowEstimator_.correctIrradiance, shadowEstimator_.correctionError};
  // Less filtering where the ratio holds more frames.
  o.sigmaFade = frame.accumulating ? frame.settings.accumulation.filterFade : 0.0f;
  o.tilesPerAxis = interleaved() ? allocated_.lightPass.interleave : 1;
  o.resolve = kInterleaveResolve;
  return o;
}

LightPassTarget LghIndirect::lightPassTarget(const IndirectFrame& frame) {
  const TileLayout layout = interleaved() ? tiles_.layout : fullLayout();
  if (shadowed()) shadowSlots_.allocate(layout.targetSize(), frame.settings.shadows.samples);
  if (interleaved())
    return {tiles_.position, tiles_.normal, layout, tiles_.irradiance, &tiles_.fragmentCounts, &shadowSlots_};
  return {frame.gbuffer.position, frame.gbuffer.normal, layout, irradiance_, &fragmentCounts_, &shadowSlots_};
}

LightStats LghIndirect::estimate(const IndirectFrame& frame) {
  resolveShadows(frame);
  const LightPassOptions options = lightPassOptions(frame);
  // Each grid light's shadow-ray targets: input lights drawn by their share of its importance (the light
  // pass reads them too, for grid lights it cannot select).
  if (drawsShadowTargets())
    frame.timed(passes::kShadowTargets, [&] {
      shadowTargetsPass_.execute({frame.lights.lights, frame.lights.count, hierarchy_}, shadowEstimator_.drawnTargets,
                                 options.frameSeed, shadowTargets_);
    });
  else
    shadowTargets_ = {};  // the rays aim at the clusters' centres
  const LightPassTarget target = lightPassTarget(frame);
  LightPassDraws draws;
  // n x n interleaving: the surfaces as n^2 tiles, each shaded by 1/n^2 of the lights.
  if (interleaved()) frame.timed(passes::kInterleaveSplit, [&] { interleavePass_.split(frame.gbuffer, tiles_); });
  // Light volumes: irradiance through the LGH, and k lights per pixel picked for shadow rays.
  frame.timed(passes::kLightPass, [&] {
    draws = lightPass_.execute({frame.lights.lights, frame.lights.count, hierarchy_, &shadowTargets_}, options, target);
  });
  // The tiles' irradiance back at full resolution, edge-aware.
  if (interleaved())
    frame.timed(passes::kInterleaveResolve, [&] {
      interleavePass_.resolve(frame.gbuffer, tiles_, kInterleaveResolve,
                              {irradiance_, options.pass.overdraw ? &fragmentCounts_ : nullptr});
    });
  // Shadow rays to the picked lights: the raw visibility ratio.
  if (shadowed())
    frame.timed(passes::kShadowRays, [&] {
      shadowRayPass_.execute({frame.scene, frame.gbuffer, frame.lights.lights, frame.lights.count, hierarchy_,
                              shadowTargets_, shadowSlots_, target.layout, target.irradiance},
                             shadowRayOptions(frame, options), {rawRatio_, sampledIrradiance_, recordedRays_});
    });
  LightStats stats;
  stats.lightsPerLevel = draws.lightsPerLevel;
  stats.levels = frame.settings.lightPass.bruteForce ? 0 : hierarchy_.grid.levels;
  return stats;
}

AccumulationSource LghIndirect::accumulation(const IndirectFrame& frame) {
  // This frame's raw irradiance and ratio, in the light pass's layout (the tiles' when interleaving).
  const int k = frame.settings.shadows.samples;
  if (interleaved()) return {tiles_.irradiance, tiles_.layout, k, {irradiance_, rawRatio_, sampledIrradiance_}};
  // Without interleaving the light pass sums every grid light at every pixel: the same each still frame.
  return {irradiance_, fullLayout(), k, {irradiance_, rawRatio_, sampledIrradiance_}, true};
}

IndirectImage LghIndirect::filter(const IndirectFrame& frame) {
  if (!shadowed()) return {&irradiance_, nullptr};
  // A-trous filter over the ratio, as a ratio estimator with the ratio's weights (less of it where the
  // ratio holds more frames), and the mean weight that corrects the irradiance.
  frame.timed(passes::kShadowFilter, [&] {
    shadowFilterPass_.execute({frame.gbuffer, rawRatio_, sampledIrradiance_}, shadowFilterOptions(frame), visibility_);
  });
  return {&irradiance_, &visibility_};
}

void LghIndirect::countWork(LightStats& stats) const {
  if (!allocated_.lightPass.overdraw) return;
  const std::vector<GLuint> counts = fragmentCounts_.readUint();
  const std::vector<glm::vec4> irradiance = irradiance_.readRGBA();
  double rasterized = 0, shaded = 0;
  unsigned largest = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    rasterized += counts[i];
    shaded += irradiance[i].a;
    largest = std::max(largest, counts[i]);
  }
  const double pixels = double(std::max<size_t>(counts.size(), 1));
  stats.rasterizedPerPixel = rasterized / pixels;
  stats.shadedPerPixel = shaded / pixels;
  stats.maxRasterized = largest;
}

const gl::Texture2D* LghIndirect::target(Aov aov) const {
  switch (aov) {
    case Aov::Irradiance:
      return &irradiance_;
    case Aov::Ratio:
    case Aov::History:  // the accumulated ratio's alpha holds its frames
      return &rawRatio_;
    case Aov::Visibility:
      return &visibility_;
    case Aov::Overdraw:
      return &fragmentCounts_;
    default:
      return nullptr;
  }
}

}  // namespace lgh
