#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/display_encode.h"
#include "shared/scene_types.h"

namespace lgh {
namespace {

struct AovName {
  Aov aov;
  const char* name;
};
constexpr AovName kAovNames[] = {{Aov::Final, "final"},         {Aov::Direct, "direct"},     {Aov::Indirect, "indirect"},
                                 {Aov::Irradiance, "irradiance"}, {Aov::Ratio, "ratio"}, {Aov::Visibility, "visibility"}, {Aov::Overdraw, "overdraw"}, {Aov::Emission, "emission"},
                                 {Aov::Albedo, "albedo"},       {Aov::Normal, "normal"},     {Aov::Position, "position"}};

// Default clamp distance d_c as a fraction of the scene's diagonal. 1e-3 left bright specks along
// creases (VPLs and S1 centres a millimetre from the next wall in the Cornell box); 1e-2 removes
// them and changes Sponza's image imperceptibly (0.4 m there).
constexpr float kDefaultClampFraction = 1e-2f;

}  // namespace

Aov parseAov(const std::string& name) {
  for (const auto& a : kAovNames)
    if (name == a.name) return a.aov;
  std::string list;
  for (const auto& a : kAovNames) list += (list.empty() ? "" : ", ") + std::string(a.name);
  throw std::invalid_argument("unknown AOV '" + name + "' (choose one of: " + list + ")");
}

std::vector<std::string> aovNames() {
  std::vector<std::string> names;
  for (const auto& a : kAovNames) names.emplace_back(a.name);
  return names;
}

bool isDataAov(Aov aov) {
  return aov == Aov::Overdraw || aov == Aov::Ratio || aov == Aov::Visibility || aov == Aov::Albedo || aov == Aov::Normal || aov == Aov::Position;
}

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
  if (!settings.camera.empty()) return scene.camera(settings.camera);
  if (!scene.cameras.empty()) return scene.cameras.front();
  return frameBounds(scene.bounds, float(settings.width) / float(settings.height));
}

Renderer::Renderer(const SceneGpu& scene, const RenderSettings& settings)
    : scene_(scene),
      settings_(settings),
      frameUniforms_(sizeof(gpu::FrameUniforms)),
      inputLightsPass_(scene),
      buildPass_(GLAD_GL_NV_shader_atomic_float != 0),
      lightPass_(GLAD_GL_NV_shader_atomic_float != 0) {
  allocateTargets();
}

void Renderer::setSettings(const RenderSettings& settings) {
  const bool resized = settings.width != settings_.width || settings.height != settings_.height ||
                       settings.interleave != settings_.interleave;
  settings_ = settings;
  if (resized) allocateTargets();
}

void Renderer::allocateTargets() {
  const int w = settings_.width, h = settings_.height;
  gbuffer_ = GBuffer(w, h);
  direct_ = gl::Texture2D(w, h, GL_RGBA32F);
  tiles_ = settings_.interleave > 1 ? Tiles(TileLayout::of(settings_.interleave, w, h)) : Tiles();
  irradiance_ = gl::Texture2D(w, h, GL_RGBA32F);
  fragmentCounts_ = gl::Texture2D(w, h, GL_R32UI);
  fragmentCounts_.clearUint(0);
  rawRatio_ = gl::Texture2D(w, h, GL_RGBA32F);
  rawRatio_.clear(glm::vec4(1.0f));
  visibility_ = gl::Texture2D(w, h, GL_RGBA32F);
  visibility_.clear(glm::vec4(1.0f));
  indirect_ = gl::Texture2D(w, h, GL_RGBA32F);
  final_ = gl::Texture2D(w, h, GL_RGBA32F);
  gl::checkErrors("allocating render targets");
}

float Renderer::clampDistance() const {
  return settings_.clampDistance > 0 ? settings_.clampDistance : kDefaultClampFraction * std::max(scene_.scene().bounds.diagonal(), 1e-6f);
}

bool Renderer::pointLightsThroughLgh() const {
  return settings_.indirect && scene_.punctualLights().size() > size_t(settings_.maxDirectLights);
}

InputLightOptions Renderer::inputLightOptions() const {
  InputLightOptions o;
  o.pointLights = pointLightsThroughLgh();
  o.emitterSamples = size_t(settings_.emitterSamples);
  o.vplBudget = size_t(settings_.vpls);
  o.bounces = settings_.bounces;
  o.seed = std::uint32_t(settings_.seed);
  return o;
}

LghBuildOptions Renderer::buildOptions() const {
  LghBuildOptions o;
  o.levels = settings_.levels;
  // The smallest top cell: 1e-4 of the scene (one light, or lights that coincide).
  o.eMin = 1e-4 * std::max(double(scene_.scene().bounds.diagonal()), 1e-6);
  return o;
}

void Renderer::uploadFrameUniforms(const CameraView& view) {
  gpu::FrameUniforms u{};
  u.viewProjection = view.viewProjection();
  u.inverseViewProjection = glm::inverse(u.viewProjection);
  u.cameraRelativeViewProjection = view.cameraRelativeViewProjection;
  u.cameraPosition = glm::vec4(view.position, 1.0f);
  u.resolution = glm::uvec4(unsigned(settings_.width), unsigned(settings_.height), frameIndex_, 0u);
  const float footprint = 2.0f / (float(settings_.height) * std::max(std::abs(view.projection[1][1]), 1e-30f));
  u.sceneScale = glm::vec4(scene_.scene().bounds.diagonal(), clampDistance(), footprint, 0.0f);
  frameUniforms_.update(&u, sizeof(u));
  frameUniforms_.bindBase(GL_UNIFORM_BUFFER, LGH_UBO_FRAME);
}

FrameStats Renderer::render(const CameraView& view) {
  FrameStats stats;
  uploadFrameUniforms(view);
  {
    gl::Profiler::Scope pass(profiler_, "G-buffer");
    gbufferPass_.execute(scene_, gbuffer_);
  }
  {
    gl::Profiler::Scope pass(profiler_, "direct light");
    directPass_.execute(scene_, gbuffer_, settings_.directShadows, pointLightsThroughLgh(), direct_);
  }
  const bool indirect = settings_.indirect;
  if (indirect) {
    // S0 and the hierarchy depend on the lights and the settings, not on the camera. A light moved
    // through SceneGpu::setPunctualLight rebuilds both, as in the paper (VPLs are not reprojected).
    const InputLightOptions lightOptions = inputLightOptions();
    const LghBuildOptions hierarchyOptions = buildOptions();
    const bool relight =
        !lightsBuilt_ || lightOptions != builtLightOptions_ || scene_.lightsVersion() != builtLightsVersion_;
    if (relight) {
      gl::Profiler::Scope pass(profiler_, "input lights");
      inputLightsPass_.execute(lightOptions, inputLights_);
      hierarchyBuilt_ = false;
    }
    // Brute force needs no hierarchy; it is built when the light pass first needs it.
    const bool rebuild = !settings_.bruteForce && (!hierarchyBuilt_ || hierarchyOptions.levels != builtHierarchyOptions_.levels);
    if (rebuild) {
      gl::Profiler::Scope pass(profiler_, "LGH build");
      buildPass_.execute(inputLights_.lights, inputLights_.count, hierarchyOptions, hierarchy_);
      hierarchyBuilt_ = true;
    }
    stats.lightsRebuilt = relight || rebuild;
    lightsBuilt_ = true;
    builtLightOptions_ = lightOptions;
    builtLightsVersion_ = scene_.lightsVersion();
    builtHierarchyOptions_ = hierarchyOptions;

    LightPassOptions options;
    options.alpha = settings_.alpha;
    options.firstLevel = settings_.startLevel;
    options.clampDistance = clampDistance();
    options.bruteForce = settings_.bruteForce;
    options.countFragments = settings_.overdraw;
    options.shadowSamples = settings_.shadowSamples;
    options.skipFinestForShadows = settings_.shadowSkipFinest;
    options.uniformSelection = settings_.shadowUniform;
    options.frameSeed = frameIndex_ * 0x9e3779b9u + unsigned(settings_.seed);
    const bool interleaved = settings_.interleave > 1;
    const TileLayout layout = interleaved ? tiles_.layout : TileLayout::of(1, settings_.width, settings_.height);
    if (options.shadowSamples > 0) shadowSlots_.allocate(layout.targetSize(), options.shadowSamples);
    if (interleaved) {
      gl::Profiler::Scope pass(profiler_, "interleave split");
      interleavePass_.split(gbuffer_, tiles_);
    }
    {
      gl::Profiler::Scope pass(profiler_, "light pass");
      LightPassTarget target =
          interleaved ? LightPassTarget{tiles_.position, tiles_.normal, layout, tiles_.irradiance, &tiles_.fragmentCounts, &shadowSlots_}
                      : LightPassTarget{gbuffer_.position, gbuffer_.normal, layout, irradiance_, &fragmentCounts_, &shadowSlots_};
      stats.lights.lightsPerLevel = lightPass_.execute(inputLights_.lights, inputLights_.count, hierarchy_, options, target).lightsPerLevel;
    }
    if (interleaved) {
      gl::Profiler::Scope pass(profiler_, "interleave resolve");
      interleavePass_.resolve(gbuffer_, tiles_, InterleaveFilter{}, settings_.overdraw, irradiance_, fragmentCounts_);
    }
    if (options.shadowSamples > 0) {
      {
        gl::Profiler::Scope pass(profiler_, "shadow rays");
        ShadowRayOptions rays;
        rays.spread = settings_.shadowSpread;
        rays.frameSeed = options.frameSeed;
        shadowRayPass_.execute(scene_, gbuffer_, shadowSlots_, layout, inputLights_.lights, hierarchy_, options, rays,
                               rawRatio_);
      }
      gl::Profiler::Scope pass(profiler_, "shadow filter");
      ShadowFilterOptions filter;
      filter.passes = settings_.filterPasses;
      filter.normalPower = settings_.filterNormalPower;
      filter.planeSigma = settings_.filterPlaneSigma;
      filter.ratioSigma = settings_.filterRatioSigma;
      shadowFilterPass_.execute(gbuffer_, rawRatio_, irradiance_, filter, visibility_);
    }
    stats.lights.inputLights = inputLights_.count;
    stats.lights.pointLights = inputLights_.pointLights;
    stats.lights.emitterSamples = inputLights_.emitterSamples;
    stats.lights.vpls = inputLights_.vpls;
    stats.lights.levels = settings_.bruteForce ? 0 : hierarchy_.grid.levels;
  }
  {
    gl::Profiler::Scope pass(profiler_, "composite");
    stats.nonFinitePixels =
        compositePass_.execute(gbuffer_, direct_, indirect ? &irradiance_ : nullptr,
                               indirect && settings_.shadowSamples > 0 ? &visibility_ : nullptr, indirect_, final_);
  }
  stats.passes = profiler_.collect();
  if (indirect && settings_.overdraw) measureOverdraw(stats.lights);
  ++frameIndex_;
  gl::checkErrors("frame");
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
  switch (aov) {
    case Aov::Final: return final_;
    case Aov::Direct: return direct_;
    case Aov::Indirect: return indirect_;
    case Aov::Irradiance: return irradiance_;
    case Aov::Ratio: return rawRatio_;
    case Aov::Visibility: return visibility_;
    case Aov::Overdraw: return fragmentCounts_;
    case Aov::Emission: return gbuffer_.emission;
    case Aov::Albedo: return gbuffer_.albedo;
    case Aov::Normal: return gbuffer_.normal;
    case Aov::Position: return gbuffer_.position;
  }
  return final_;
}

ImageRGBA Renderer::readImage(Aov aov) const {
  if (aov == Aov::Overdraw) {
    // Fragments per pixel as a heat map scaled to the frame's largest count (the paper's Fig. 5).
    const std::vector<GLuint> counts = fragmentCounts_.readUint();
    const GLuint largest = std::max<GLuint>(1, *std::max_element(counts.begin(), counts.end()));
    std::vector<glm::vec4> colors(counts.size());
    for (size_t i = 0; i < counts.size(); ++i) colors[i] = glm::vec4(gpu::heatColor(float(counts[i]) / float(largest)), 1.0f);
    return fromGLRows(fragmentCounts_.width(), fragmentCounts_.height(), colors);
  }
  const gl::Texture2D& t = texture(aov);
  std::vector<glm::vec4> pixels = t.readRGBA();
  if (aov == Aov::Ratio || aov == Aov::Visibility)  // the ratio (r) as grey
    for (glm::vec4& p : pixels) p = glm::vec4(glm::vec3(p.r), 1.0f);
  return fromGLRows(t.width(), t.height(), std::move(pixels));
}

}  // namespace lgh
