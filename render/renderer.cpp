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

// Counts per pixel as a heat map scaled to the largest (at least 1), as the viewer shows them.
std::vector<glm::vec4> heatMap(const std::vector<float>& counts) {
  float largest = 1.0f;
  for (float c : counts) largest = std::max(largest, c);
  std::vector<glm::vec4> colors;
  colors.reserve(counts.size());
  for (float c : counts) colors.push_back(glm::vec4(gpu::heatColor(c / largest), 1.0f));
  return colors;
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
      lgh_(GLAD_GL_NV_shader_atomic_float != 0) {
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
  return width == o.width && height == o.height && interleave == o.interleave && method == o.method &&
         rtslcDenoiser == o.rtslcDenoiser && shadowed == o.shadowed && overdraw == o.overdraw &&
         accumulating == o.accumulating;
}

Renderer::Configuration Renderer::configuration() const {
  Configuration c;
  c.width = settings_.image.width;
  c.height = settings_.image.height;
  c.interleave = settings_.lightPass.interleave;
  c.method = settings_.indirectMethod;
  c.rtslcDenoiser = settings_.rtslc.denoiser;
  c.shadowed = settings_.shadows.samples > 0;
  c.overdraw = settings_.lightPass.overdraw;
  c.accumulating = accumulating();
  return c;
}

void Renderer::allocateTargets() {
  const Configuration c = configured_ = configuration();
  // What the old configuration held goes before the new is allocated: a switch holds one set at a time.
  gbuffer_ = {};
  for (gl::Texture2D* t : {&direct_, &indirect_, &final_, &neutralAov_}) *t = {};
  // The method chosen once here; the one that is off frees all it holds, and S0 goes without either.
  method_ = c.method == IndirectMethod::Lgh     ? static_cast<IndirectLight*>(&lgh_)
            : c.method == IndirectMethod::Rtslc ? static_cast<IndirectLight*>(&rtslc_)
                                                : nullptr;
  if (method_ != &lgh_) lgh_.release(builds_);
  if (method_ != &rtslc_) rtslc_.release(builds_);
  if (!method_) {
    inputLights_ = {};
    builds_.freedInputLights();
  }
  if (!c.accumulating) accumulationPass_.release();
  if (method_) method_->allocate(settings_);
  gbuffer_ = GBuffer(c.width, c.height);
  auto make = [&](const char* owner, const char* name) {
    return gl::Texture2D({owner, name, kImageSize}, c.width, c.height, GL_RGBA32F);
  };
  direct_ = make(passes::kDirectLight, "direct");
  indirect_ = make(passes::kComposite, "indirect");
  final_ = make(passes::kComposite, "final");
  gl::checkErrors("allocating render targets");
}

float Renderer::clampDistance() const {
  return settings_.clampDistance > 0 ? settings_.clampDistance
                                     : kDefaultClampFraction * std::max(scene_.scene().bounds.diagonal(), 1e-6f);
}

bool Renderer::pointLightsInS0() const {
  return method_ && scene_.punctualLights().size() > size_t(settings_.inputLights.maxDirectLights);
}

LghBuildOptions Renderer::buildOptions() const { return LghIndirect::buildOptions(scene_, settings_); }

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

IndirectFrame Renderer::indirectFrame() {
  return {scene_, settings_, gbuffer_, inputLights_, clampDistance(), frameIndex_, accumulating(), profiler_};
}

FrameStats Renderer::render(const CameraView& view) {
  FrameStats stats;
  if (configuration() != configured_) allocateTargets();
  uploadFrameUniforms(view);
  // Surfaces seen by the camera: position, normal, albedo, emission.
  timed(passes::kGBuffer, [&] { gbufferPass_.execute(scene_, gbuffer_); });
  // Punctual lights, one shadow ray each (except point lights that go into S0).
  timed(passes::kDirectLight,
        [&] { directPass_.execute(scene_, gbuffer_, settings_.directShadows, pointLightsInS0(), direct_); });
  IndirectImage indirect;
  if (method_) {
    const IndirectFrame frame = indirectFrame();
    // S0 (VPLs, emitter samples, many point lights) and the structure the method draws from it (the
    // hierarchy, the light tree), when out of date.
    stats.lightsRebuilt = updateLights(frame);
    const HistoryUpdate history = updateAccumulation(stats.lightsRebuilt, view);
    stats.accumulatedFrames = history.stillFrames;
    // This frame's raw estimate (render/indirect/): the LGH's light volumes with k shadow samples picked per
    // pixel and their shadow rays, or the lightcuts' n shadowed light samples per pixel.
    stats.lights = method_->estimate(frame);
    // Temporal accumulation: the raw estimate added to the history reprojected from the last frame; the
    // accumulated estimate replaces it for the filter and the composite.
    if (accumulating()) timed(passes::kAccumulation, [&] { accumulate(frame, view, history.lightsMoved); });
    // The estimate denoised: the LGH's ratio filter, or the lightcuts' variance-guided one.
    indirect = method_->filter(frame);
  }
  // Emission + direct + albedo / pi x irradiance x visibility; non-finite pixels written black, counted.
  timed(passes::kComposite, [&] {
    stats.nonFinitePixels =
        compositePass_.execute({gbuffer_, direct_, indirect.irradiance, indirect.visibility}, {indirect_, final_});
  });
  stats.passes = profiler_.collect();
  // The BVH that SceneGpu::follow rebuilt for this frame's moved vertices: timed where it ran, before the frame.
  if (scene_.geometryVersion() != geometryVersion_) {
    stats.passes.insert(stats.passes.begin(), gl::PassTiming{passes::kBvhBuild, 0.0, scene_.bvhBuildMs()});
    geometryVersion_ = scene_.geometryVersion();
  }
  if (method_) {
    stats.lights.inputLights = inputLights_.count;
    stats.lights.pointLights = inputLights_.pointLights;
    stats.lights.emitterSamples = inputLights_.emitterSamples;
    stats.lights.vpls = inputLights_.vpls;
    method_->countWork(stats.lights);  // read back after the timings
  }
  ++frameIndex_;
  gl::checkErrors("frame");
  return stats;
}

void Renderer::accumulate(const IndirectFrame& frame, const CameraView& view, bool lightsMoved) {
  const AccumulationSource source = method_->accumulation(frame);
  accumulationPass_.execute({gbuffer_, view, source.rawIrradiance, source.layout, source.shadowSamples,
                             kInterleaveResolve, lightsMoved, source.wholeIrradiance},
                            settings_.accumulation, source.targets);
}

void Renderer::restartAccumulation() {
  accumulationPass_.restart();
  accumulatedFrames_ = 0;
}

Renderer::HistoryUpdate Renderer::updateAccumulation(bool lightsRebuilt, const CameraView& view) {
  HistoryUpdate update;
  if (!accumulating()) {
    restartAccumulation();
    return update;
  }
  std::string key = estimateKey(settings_);
  // The history's sums belong to the settings they were made with. Lights rebuilt with the same settings
  // moved (a light, or the geometry, with the VPLs drawn from the same random numbers): the history is
  // restarted, or kept where each pixel's test finds the lighting unchanged (AccumulationSettings::motion).
  if (key != accumulationKey_ || (lightsRebuilt && settings_.accumulation.motion == HistoryMotion::Restart)) {
    restartAccumulation();
  } else if (lightsRebuilt) {
    update.lightsMoved = true;
    accumulatedFrames_ = 0;  // the count is of still frames
  }
  accumulationKey_ = std::move(key);
  // A moved camera keeps the reprojected history where the surfaces match, but this count is of the
  // still frames only.
  if (accumulatedFrames_ > 0 && !sameView(view, accumulationView_)) accumulatedFrames_ = 0;
  accumulationView_ = view;
  accumulatedFrames_ = std::min(accumulatedFrames_ + 1, settings_.accumulation.maxFrames);
  update.stillFrames = accumulatedFrames_;
  return update;
}

bool Renderer::updateLights(const IndirectFrame& frame) {
  const InputLightKey key{settings_.inputLights, pointLightsInS0(), scene_.lightsVersion(), scene_.geometryVersion()};
  // A moved light or a moved mesh rebuilds S0 and the structure over it, as in the paper (VPLs are not
  // reprojected): from the same random numbers, so that a small move moves the VPLs a little.
  const bool inputLights = builds_.plan(key, settings_.hierarchy.levels, false).inputLights;
  if (inputLights) {
    timed(passes::kInputLights, [&] { inputLightsPass_.execute(key.settings, key.pointLightsToS0, inputLights_); });
    builds_.builtInputLights(key);
  }
  const bool structure = method_->updateStructure(frame, key, builds_);
  return inputLights || structure;
}

const gl::Texture2D& Renderer::texture(Aov aov) const {
  const gl::Texture2D* t = target(aov);
  if (t && *t) return *t;
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

const gl::Texture2D* Renderer::target(Aov aov) const {
  switch (aov) {
    case Aov::Final:
      return &final_;
    case Aov::Direct:
      return &direct_;
    case Aov::Indirect:
      return &indirect_;
    case Aov::Emission:
      return &gbuffer_.emission;
    case Aov::Albedo:
      return &gbuffer_.albedo;
    case Aov::Normal:
      return &gbuffer_.normal;
    case Aov::Position:
      return &gbuffer_.position;
    case Aov::History:  // the frames in the accumulated history, in the alpha of the method's target
      return accumulating() && method_ ? method_->target(aov) : nullptr;
    case Aov::Irradiance:  // the method's: with the lightcuts shadowed, and filtered as the composite uses it
    case Aov::Ratio:
    case Aov::Visibility:
    case Aov::Overdraw:
      return method_ ? method_->target(aov) : nullptr;
  }
  return nullptr;
}

ImageRGBA Renderer::readImage(Aov aov) const {
  if (aov == Aov::History || aov == Aov::Overdraw) {
    // The frames in each pixel's history (alpha), or its fragments (the paper's Fig. 5).
    std::vector<float> counts;
    if (aov == Aov::History)
      for (const glm::vec4& p : texture(aov).readRGBA()) counts.push_back(p.a);
    else
      for (GLuint c : texture(aov).readUint()) counts.push_back(float(c));
    return fromGLRows(settings_.image.width, settings_.image.height, heatMap(counts));
  }
  const gl::Texture2D& t = texture(aov);
  std::vector<glm::vec4> pixels = t.readRGBA();
  if (aov == Aov::Ratio || aov == Aov::Visibility)  // the ratio (r) as grey
    for (glm::vec4& p : pixels) p = glm::vec4(glm::vec3(p.r), 1.0f);
  return fromGLRows(t.width(), t.height(), std::move(pixels));
}

}  // namespace lgh
