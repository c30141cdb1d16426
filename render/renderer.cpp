#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/display_encode.h"
#include "shared/scene_types.h"

namespace lgh {
namespace {

// Default clamp distance d_c as a fraction of the scene's diagonal. 1e-3 left bright specks along
// creases (VPLs and S1 centres a millimetre from the next wall in the Cornell box); 1e-2 removes
// them and changes Sponza's image imperceptibly (0.4 m there).
constexpr float kDefaultClampFraction = 1e-2f;

// The settings an accumulated history depends on, as text: all but those declared to keep it
// (SettingInfo::keepsHistory).
std::string estimateKey(RenderSettings settings) {
  std::ostringstream key;
  key.precision(9);
  visitSettings(settings, [&](const auto& value, const SettingInfo& info) {
    if (!info.keepsHistory) key << info.name << '=' << value << ';';
  });
  return key.str();
}

bool sameView(const CameraView& a, const CameraView& b) {
  return a.position == b.position && a.worldViewProjection == b.worldViewProjection &&
         a.cameraRelativeViewProjection == b.cameraRelativeViewProjection;
}

}  // namespace

double FrameStats::totalMs() const {
  double total = 0;
  for (const auto& p : passes) total += p.wallMs > 0 ? p.wallMs : p.gpuMs;
  return total;
}

double FrameStats::passMs(const std::string& name) const {
  for (const auto& p : passes)
    if (p.name == name) return p.wallMs > 0 ? p.wallMs : p.gpuMs;
  return 0;
}

Camera resolveCamera(const Scene& scene, const RenderSettings& settings) {
  if (!settings.image.camera.empty()) return scene.camera(settings.image.camera);
  if (!scene.cameras.empty()) return scene.cameras.front();
  return frameBounds(scene.bounds, float(settings.image.width) / float(settings.image.height));
}

Renderer::Renderer(const SceneGpu& scene, const RenderSettings& settings)
    : scene_(scene),
      settings_(settings),
      frameUniforms_({passes::kFrameSetup, "frame uniforms"}, sizeof(gpu::FrameUniforms)),
      inputLightsPass_(scene),
      buildPass_(GLAD_GL_NV_shader_atomic_float != 0),
      lightPass_(GLAD_GL_NV_shader_atomic_float != 0) {
  gl::memory().setLimit(size_t(double(settings.gpuMemoryLimit) * 1e6));
  allocateTargets();
}

void Renderer::setSettings(const RenderSettings& settings) {
  const bool resized = settings.image.width != settings_.image.width ||
                       settings.image.height != settings_.image.height ||
                       settings.lightPass.interleave != settings_.lightPass.interleave;
  settings_ = settings;
  gl::memory().setLimit(size_t(double(settings.gpuMemoryLimit) * 1e6));
  if (resized) restartAccumulation();
}

bool Renderer::Configuration::operator==(const Configuration& o) const {
  return width == o.width && height == o.height && interleave == o.interleave && lgh == o.lgh &&
         hierarchy == o.hierarchy && shadowed == o.shadowed && lightcuts == o.lightcuts && overdraw == o.overdraw &&
         accumulating == o.accumulating;
}

Renderer::Configuration Renderer::configuration() const {
  Configuration c;
  c.width = settings_.image.width;
  c.height = settings_.image.height;
  c.interleave = settings_.lightPass.interleave;
  c.lightcuts = settings_.indirect && lightcuts();
  c.lgh = settings_.indirect && !c.lightcuts;
  c.hierarchy = c.lgh && !settings_.lightPass.bruteForce;
  c.shadowed = c.lgh && shadowed();
  c.overdraw = c.lgh && settings_.lightPass.overdraw;
  c.accumulating = accumulating();
  return c;
}

void Renderer::allocateTargets() {
  const Configuration c = configured_ = configuration();
  const int w = c.width, h = c.height;
  auto make = [&](const char* owner, const char* name, GLenum format) {
    return gl::Texture2D({owner, name, kImageSize}, w, h, format);
  };
  // What the old configuration held goes before the new is allocated: a switch holds one set at a time.
  gbuffer_ = {};
  tiles_ = {};
  for (gl::Texture2D* t : {&direct_, &indirect_, &final_, &irradiance_, &fragmentCounts_, &rawRatio_,
                           &sampledIrradiance_, &visibility_, &filteredIrradiance_, &neutralAov_})
    *t = {};
  releaseUnused();
  gbuffer_ = GBuffer(w, h);
  direct_ = make(passes::kDirectLight, "direct", GL_RGBA32F);
  indirect_ = make(passes::kComposite, "indirect", GL_RGBA32F);
  final_ = make(passes::kComposite, "final", GL_RGBA32F);
  // The rest only where the configuration's passes write them.
  if (c.lgh && c.interleave > 1) tiles_ = Tiles(TileLayout::of(c.interleave, w, h), c.overdraw);
  if (c.lgh || c.lightcuts)
    irradiance_ = make(c.lgh ? passes::kLightPass : passes::kLightcutSampling, "irradiance", GL_RGBA32F);
  if (c.overdraw) {
    fragmentCounts_ = make(passes::kLightPass, "fragment counts", GL_R32UI);
    fragmentCounts_.clearUint(0);
  }
  // The raw ratio and the sampled irradiance: the shadow rays' outputs, and the accumulation's (unshadowed,
  // and for the lightcuts, a ratio of 1 beside the irradiance).
  if (c.shadowed || c.accumulating) {
    const char* owner = c.shadowed ? passes::kShadowRays : passes::kAccumulation;
    rawRatio_ = make(owner, "ratio", GL_RGBA32F);
    rawRatio_.clear(glm::vec4(1.0f));
    sampledIrradiance_ = make(owner, "sampled irradiance", GL_R32F);
    sampledIrradiance_.clear(glm::vec4(0.0f));
  }
  if (c.shadowed) visibility_ = make(passes::kShadowFilter, "visibility", GL_RGBA32F);
  if (c.lightcuts) filteredIrradiance_ = make(passes::kIrradianceFilter, "filtered irradiance", GL_RGBA32F);
  gl::checkErrors("allocating render targets");
}

void Renderer::releaseUnused() {
  const Configuration& c = configured_;
  if (!c.accumulating) accumulationPass_.release();
  if (!c.shadowed) {
    shadowSlots_ = {};
    shadowTargets_ = {};
    shadowTargetsPass_.release();
    shadowRayPass_.release();
    shadowFilterPass_.release();
  }
  if (!c.lgh) lightPass_.release();
  if (!c.hierarchy) {
    hierarchy_ = {};
    builds_.freedHierarchy();
  }
  if (!c.lightcuts) {
    lightTree_ = {};
    builds_.freedLightTree();
    rtslcPass_.release();
    irradianceFilterPass_.release();
  }
  if (!c.lgh && !c.lightcuts) {
    inputLights_ = {};
    builds_.freedInputLights();
  }
}

float Renderer::clampDistance() const {
  return settings_.clampDistance > 0 ? settings_.clampDistance
                                     : kDefaultClampFraction * std::max(scene_.scene().bounds.diagonal(), 1e-6f);
}

bool Renderer::lightcuts() const {
  if (!isChoice(kIndirectMethodChoices, settings_.indirectMethod))
    throw std::invalid_argument("unknown indirect method '" + settings_.indirectMethod + "' (choose lgh or rtslc)");
  return settings_.indirectMethod == "rtslc";
}

bool Renderer::pointLightsThroughLgh() const {
  return settings_.indirect && scene_.punctualLights().size() > size_t(settings_.inputLights.maxDirectLights);
}

LghBuildOptions Renderer::buildOptions() const {
  LghBuildOptions o;
  o.levels = settings_.hierarchy.levels;
  o.eMin = minTopCellFor(scene_.scene().bounds.diagonal());
  return o;
}

LightPassOptions Renderer::lightPassOptions() const {
  LightPassOptions o;
  o.pass = settings_.lightPass;
  o.shadows = shadowEstimator_;
  o.clampDistance = clampDistance();
  o.sceneSize = std::max(scene_.scene().bounds.diagonal(), 1e-6f);
  o.frameSeed = frameIndex_ * 0x9e3779b9u + unsigned(settings_.inputLights.seed);
  // Accumulating, consecutive frames deal the lights to the n x n tiles shifted by one more, so any n^2
  // of them give every pixel every light exactly once (without, frame after frame the same dealing).
  o.tileRotation = accumulating() ? frameIndex_ : 0u;
  return o;
}

ShadowRayOptions Renderer::shadowRayOptions(const LightPassOptions& lightPass) {
  ShadowRayOptions o;
  o.shadows = lightPass.shadows;
  o.alpha = lightPass.pass.alpha;
  o.startLevel = lightPass.pass.startLevel;
  o.bruteForce = lightPass.pass.bruteForce;
  o.clampDistance = lightPass.clampDistance;
  o.frameSeed = lightPass.frameSeed;
  return o;
}

ShadowFilterOptions Renderer::shadowFilterOptions() const {
  ShadowFilterOptions o;
  o.filter = settings_.filter;
  o.correction = {shadowEstimator_.correctIrradiance, shadowEstimator_.correctionError};
  // Less filtering where the ratio holds more frames.
  o.sigmaFade = accumulating() ? settings_.accumulation.filterFade : 0.0f;
  o.tilesPerAxis = interleaved() ? settings_.lightPass.interleave : 1;
  o.resolve = kInterleaveResolve;
  return o;
}

RtslcOptions Renderer::rtslcOptions() const {
  RtslcOptions o;
  o.settings = settings_.rtslc;
  o.clampDistance = clampDistance();
  o.frameSeed = frameIndex_ * 0x9e3779b9u + unsigned(settings_.inputLights.seed);
  return o;
}

LightPassTarget Renderer::lightPassTarget() {
  const TileLayout layout =
      interleaved() ? tiles_.layout : TileLayout::of(1, settings_.image.width, settings_.image.height);
  if (shadowed()) shadowSlots_.allocate(layout.targetSize(), settings_.shadows.samples);
  if (interleaved())
    return {tiles_.position, tiles_.normal, layout, tiles_.irradiance, &tiles_.fragmentCounts, &shadowSlots_};
  return {gbuffer_.position, gbuffer_.normal, layout, irradiance_, &fragmentCounts_, &shadowSlots_};
}

void Renderer::uploadFrameUniforms(const CameraView& view) {
  const ImageSettings& image = settings_.image;
  gpu::FrameUniforms u{};
  u.viewProjection = view.viewProjection();
  u.inverseViewProjection = glm::inverse(u.viewProjection);
  u.cameraRelativeViewProjection = view.cameraRelativeViewProjection;
  u.cameraPosition = glm::vec4(view.position, 1.0f);
  u.resolution = glm::uvec4(unsigned(image.width), unsigned(image.height), frameIndex_, 0u);
  const float footprint = 2.0f / (float(image.height) * std::max(std::abs(view.projection[1][1]), 1e-30f));
  u.sceneScale = glm::vec4(scene_.scene().bounds.diagonal(), clampDistance(), footprint, view.znear);
  frameUniforms_.update(&u, sizeof(u));
  frameUniforms_.bindBase(GL_UNIFORM_BUFFER, LGH_UBO_FRAME);
}

FrameStats Renderer::render(const CameraView& view) {
  FrameStats stats;
  if (configuration() != configured_) allocateTargets();
  uploadFrameUniforms(view);
  // Surfaces seen by the camera: position, normal, albedo, emission.
  timed(passes::kGBuffer, [&] { gbufferPass_.execute(scene_, gbuffer_); });
  // Punctual lights, one shadow ray each (except point lights that go through the LGH).
  timed(passes::kDirectLight,
        [&] { directPass_.execute(scene_, gbuffer_, settings_.directShadows, pointLightsThroughLgh(), direct_); });
  if (settings_.indirect) {
    // S0 (VPLs, emitter samples, many point lights) and its hierarchy, when out of date.
    stats.lightsRebuilt = updateLights();
    stats.accumulatedFrames = updateAccumulation(stats.lightsRebuilt, view);
  }
  if (settings_.indirect && lightcuts()) {
    // Stochastic lightcuts, the peer method (docs/design.md §12): a cut of the light tree per pixel block, one
    // light drawn under each cut node per pixel with its shadow ray: the shadowed irradiance, unbiased.
    const RtslcInputs in{scene_, gbuffer_, inputLights_.lights, inputLights_.count, lightTree_};
    const RtslcOptions options = rtslcOptions();
    timed(passes::kLightcutCuts, [&] { rtslcPass_.selectCuts(in, options); });
    timed(passes::kLightcutSampling, [&] { rtslcPass_.sample(in, options, {irradiance_}); });
    // Temporal accumulation of the estimate, as the LGH's irradiance is accumulated (each frame is unbiased,
    // or with interleaving every m^2 frames: nothing to correct).
    if (accumulating())
      timed(passes::kAccumulation, [&] {
        const TileLayout layout = TileLayout::of(1, settings_.image.width, settings_.image.height);
        accumulationPass_.execute({gbuffer_, view, irradiance_, layout, 0, kInterleaveResolve}, settings_.accumulation,
                                  {irradiance_, rawRatio_, sampledIrradiance_});
      });
    // The shadow filter's a-trous passes over the irradiance itself (less of it over more frames).
    timed(passes::kIrradianceFilter, [&] {
      const bool moments = accumulating();
      irradianceFilterPass_.execute(
          gbuffer_, irradiance_,
          {settings_.filter.passes, settings_.rtslc, moments ? settings_.accumulation.filterFade : 0.0f,
           moments ? &rawRatio_ : nullptr},
          filteredIrradiance_);
    });
    stats.lights = lightStats({});
  } else if (settings_.indirect) {
    resolveShadows();
    const LightPassOptions options = lightPassOptions();
    // Each grid light's shadow-ray targets: input lights drawn by their share of its importance (the light
    // pass reads them too, for grid lights it cannot select).
    if (drawsShadowTargets())
      timed(passes::kShadowTargets, [&] {
        shadowTargetsPass_.execute({inputLights_.lights, inputLights_.count, hierarchy_}, shadowEstimator_.drawnTargets,
                                   options.frameSeed, shadowTargets_);
      });
    else
      shadowTargets_ = {};  // the rays aim at the clusters' centres
    const LightPassTarget target = lightPassTarget();
    LightPassDraws draws;
    // n x n interleaving: the surfaces as n^2 tiles, each shaded by 1/n^2 of the lights.
    if (interleaved()) timed(passes::kInterleaveSplit, [&] { interleavePass_.split(gbuffer_, tiles_); });
    // Light volumes: irradiance through the LGH, and k lights per pixel picked for shadow rays.
    timed(passes::kLightPass, [&] {
      draws =
          lightPass_.execute({inputLights_.lights, inputLights_.count, hierarchy_, &shadowTargets_}, options, target);
    });
    // The tiles' irradiance back at full resolution, edge-aware.
    if (interleaved())
      timed(passes::kInterleaveResolve, [&] {
        interleavePass_.resolve(gbuffer_, tiles_, kInterleaveResolve,
                                {irradiance_, options.pass.overdraw ? &fragmentCounts_ : nullptr});
      });
    // Shadow rays to the picked lights: the raw visibility ratio.
    if (shadowed())
      timed(passes::kShadowRays, [&] {
        shadowRayPass_.execute({scene_, gbuffer_, inputLights_.lights, inputLights_.count, hierarchy_, shadowTargets_,
                                shadowSlots_, target.layout, target.irradiance},
                               shadowRayOptions(options), {rawRatio_, sampledIrradiance_});
      });
    // Temporal accumulation: this frame's raw irradiance and ratio added to the history reprojected from
    // the last frame; the accumulated estimates replace them for the filter and the composite.
    if (accumulating())
      timed(passes::kAccumulation, [&] {
        accumulationPass_.execute(
            {gbuffer_, view, target.irradiance, target.layout, settings_.shadows.samples, kInterleaveResolve},
            settings_.accumulation, {irradiance_, rawRatio_, sampledIrradiance_});
      });
    // A-trous filter over the ratio, as a ratio estimator with the ratio's weights (less of it where the
    // ratio holds more frames), and the mean weight that corrects the irradiance.
    if (shadowed())
      timed(passes::kShadowFilter, [&] {
        shadowFilterPass_.execute({gbuffer_, rawRatio_, sampledIrradiance_}, shadowFilterOptions(), visibility_);
      });
    stats.lights = lightStats(draws);
  }
  // Emission + direct + albedo / pi x irradiance x visibility; non-finite pixels written black, counted.
  timed(passes::kComposite, [&] {
    const bool lgh = settings_.indirect && !lightcuts();
    const CompositeInputs in{gbuffer_, direct_,
                             settings_.indirect ? (lgh ? &irradiance_ : &filteredIrradiance_) : nullptr,
                             lgh && shadowed() ? &visibility_ : nullptr};
    stats.nonFinitePixels = compositePass_.execute(in, {indirect_, final_});
  });
  stats.passes = profiler_.collect();
  if (settings_.indirect && settings_.lightPass.overdraw) measureOverdraw(stats.lights);
  ++frameIndex_;
  gl::checkErrors("frame");
  return stats;
}

void Renderer::resolveShadows() {
  ShadowEstimatorLimits limits;
  limits.bruteForce = settings_.lightPass.bruteForce;
  limits.inputLights = inputLights_.count;
  limits.inputLightsPerBlock = lightPass_.inputLightsPerBlock();
  ResolvedShadowEstimator resolved = resolveShadowEstimator(settings_.shadows, limits);
  for (const std::string& line : resolved.switchedOff)
    if (reportedLimits_.insert(line).second) std::fprintf(stderr, "lgh: %s\n", line.c_str());
  shadowEstimator_ = resolved.estimator;
}

void Renderer::restartAccumulation() {
  accumulationPass_.restart();
  accumulatedFrames_ = 0;
}

int Renderer::updateAccumulation(bool lightsRebuilt, const CameraView& view) {
  if (!accumulating()) {
    restartAccumulation();
    return 0;
  }
  std::string key = estimateKey(settings_);
  // The history's sums belong to the lights and settings they were made with (VPLs are not reprojected).
  if (lightsRebuilt || key != accumulationKey_) restartAccumulation();
  accumulationKey_ = std::move(key);
  // A moved camera keeps the reprojected history where the surfaces match, but this count is of the
  // still frames only.
  if (accumulatedFrames_ > 0 && !sameView(view, accumulationView_)) accumulatedFrames_ = 0;
  accumulationView_ = view;
  accumulatedFrames_ = std::min(accumulatedFrames_ + 1, settings_.accumulation.maxFrames);
  return accumulatedFrames_;
}

bool Renderer::updateLights() {
  const InputLightKey key{settings_.inputLights, pointLightsThroughLgh(), scene_.lightsVersion()};
  const LghBuildOptions hierarchyOptions = buildOptions();
  const LightBuilds::Plan plan =
      builds_.plan(key, hierarchyOptions.levels, !settings_.lightPass.bruteForce && !lightcuts(), lightcuts());
  // A light moved through SceneGpu::setPunctualLight rebuilds both, as in the paper (VPLs are not reprojected).
  if (plan.inputLights) {
    timed(passes::kInputLights, [&] { inputLightsPass_.execute(key.settings, key.pointLightsToS0, inputLights_); });
    builds_.builtInputLights(key);
  }
  if (plan.hierarchy) {
    timed(passes::kLghBuild,
          [&] { buildPass_.execute(inputLights_.lights, inputLights_.count, hierarchyOptions, hierarchy_); });
    builds_.builtHierarchy(hierarchyOptions.levels);
  }
  if (plan.lightTree) {
    timed(passes::kLightTreeBuild,
          [&] { lightTreePass_.execute(inputLights_.lights, inputLights_.count, lightTree_); });
    builds_.builtLightTree();
  }
  return plan.inputLights || plan.hierarchy || plan.lightTree;
}

LightStats Renderer::lightStats(const LightPassDraws& draws) const {
  LightStats stats;
  stats.lightsPerLevel = draws.lightsPerLevel;
  stats.inputLights = inputLights_.count;
  stats.pointLights = inputLights_.pointLights;
  stats.emitterSamples = inputLights_.emitterSamples;
  stats.vpls = inputLights_.vpls;
  stats.levels = settings_.lightPass.bruteForce || lightcuts() ? 0 : hierarchy_.grid.levels;
  return stats;
}

void Renderer::measureOverdraw(LightStats& stats) const {
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

const gl::Texture2D& Renderer::texture(Aov aov) const {
  const gl::Texture2D& t = target(aov);
  if (t) return t;
  const bool counts = aov == Aov::Overdraw;
  const float value = aov == Aov::Ratio || aov == Aov::Visibility ? 1.0f : 0.0f;
  // Made once per configuration (allocateTargets frees it), refilled per call: the viewer asks every frame.
  const GLenum format = counts ? GL_R32UI : GL_RGBA32F;
  if (!neutralAov_ || neutralAov_.format() != format)
    neutralAov_ = gl::Texture2D({passes::kComposite, "neutral AOV", kImageSize}, settings_.image.width,
                                settings_.image.height, format);
  if (counts)
    neutralAov_.clearUint(0);
  else
    neutralAov_.clear(glm::vec4(value));
  return neutralAov_;
}

const gl::Texture2D& Renderer::target(Aov aov) const {
  switch (aov) {
    case Aov::Final:
      return final_;
    case Aov::Direct:
      return direct_;
    case Aov::Indirect:
      return indirect_;
    case Aov::Irradiance:  // the lightcuts' is shadowed, and filtered as the composite uses it
      return settings_.indirect && lightcuts() ? filteredIrradiance_ : irradiance_;
    case Aov::Ratio:
      return rawRatio_;
    case Aov::Visibility:
      return visibility_;
    case Aov::Overdraw:
      return fragmentCounts_;
    case Aov::Emission:
      return gbuffer_.emission;
    case Aov::Albedo:
      return gbuffer_.albedo;
    case Aov::Normal:
      return gbuffer_.normal;
    case Aov::Position:
      return gbuffer_.position;
  }
  return final_;
}

ImageRGBA Renderer::readImage(Aov aov) const {
  if (aov == Aov::Overdraw) {
    // Fragments per pixel as a heat map scaled to the frame's largest count (the paper's Fig. 5).
    const std::vector<GLuint> counts = texture(aov).readUint();
    const GLuint largest = std::max<GLuint>(1, *std::max_element(counts.begin(), counts.end()));
    std::vector<glm::vec4> colors(counts.size());
    for (size_t i = 0; i < counts.size(); ++i)
      colors[i] = glm::vec4(gpu::heatColor(float(counts[i]) / float(largest)), 1.0f);
    return fromGLRows(settings_.image.width, settings_.image.height, colors);
  }
  const gl::Texture2D& t = texture(aov);
  std::vector<glm::vec4> pixels = t.readRGBA();
  if (aov == Aov::Ratio || aov == Aov::Visibility)  // the ratio (r) as grey
    for (glm::vec4& p : pixels) p = glm::vec4(glm::vec3(p.r), 1.0f);
  return fromGLRows(t.width(), t.height(), std::move(pixels));
}

}  // namespace lgh
