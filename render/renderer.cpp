#include "render/renderer.h"

#include <stdexcept>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/scene_types.h"

namespace lgh {
namespace {

struct AovName {
  Aov aov;
  const char* name;
};
constexpr AovName kAovNames[] = {{Aov::Final, "final"},       {Aov::Direct, "direct"}, {Aov::Emission, "emission"},
                                 {Aov::Albedo, "albedo"},     {Aov::Normal, "normal"}, {Aov::Position, "position"}};

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

double FrameStats::totalMs() const {
  double total = 0;
  for (const auto& p : passes) total += p.wallMs > 0 ? p.wallMs : p.gpuMs;
  return total;
}

Camera resolveCamera(const Scene& scene, const RenderSettings& settings) {
  if (!settings.camera.empty()) return scene.camera(settings.camera);
  if (!scene.cameras.empty()) return scene.cameras.front();
  return frameBounds(scene.bounds, float(settings.width) / float(settings.height));
}

Renderer::Renderer(const SceneGpu& scene, const RenderSettings& settings)
    : scene_(scene), settings_(settings), frameUniforms_(sizeof(gpu::FrameUniforms)) {
  allocateTargets();
}

void Renderer::setSettings(const RenderSettings& settings) {
  const bool resized = settings.width != settings_.width || settings.height != settings_.height;
  settings_ = settings;
  if (resized) allocateTargets();
}

void Renderer::allocateTargets() {
  gbuffer_ = GBuffer(settings_.width, settings_.height);
  direct_ = gl::Texture2D(settings_.width, settings_.height, GL_RGBA32F);
  final_ = gl::Texture2D(settings_.width, settings_.height, GL_RGBA32F);
  gl::checkErrors("allocating render targets");
}

float Renderer::clampDistance() const {
  return settings_.clampDistance > 0 ? settings_.clampDistance : 1e-3f * std::max(scene_.scene().bounds.diagonal(), 1e-6f);
}

void Renderer::uploadFrameUniforms(const CameraView& view) {
  gpu::FrameUniforms u{};
  u.viewProjection = view.viewProjection();
  u.inverseViewProjection = glm::inverse(u.viewProjection);
  u.cameraPosition = glm::vec4(view.position, 1.0f);
  u.resolution = glm::uvec4(unsigned(settings_.width), unsigned(settings_.height), frameIndex_, 0u);
  u.sceneScale = glm::vec4(scene_.scene().bounds.diagonal(), clampDistance(), 0.0f, 0.0f);
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
    directPass_.execute(scene_, gbuffer_, settings_.directShadows, direct_);
  }
  {
    gl::Profiler::Scope pass(profiler_, "composite");
    stats.nonFinitePixels = compositePass_.execute(gbuffer_, direct_, nullptr, nullptr, final_);
  }
  stats.passes = profiler_.collect();
  ++frameIndex_;
  gl::checkErrors("frame");
  return stats;
}

const gl::Texture2D& Renderer::texture(Aov aov) const {
  switch (aov) {
    case Aov::Final: return final_;
    case Aov::Direct: return direct_;
    case Aov::Emission: return gbuffer_.emission;
    case Aov::Albedo: return gbuffer_.albedo;
    case Aov::Normal: return gbuffer_.normal;
    case Aov::Position: return gbuffer_.position;
  }
  return final_;
}

ImageRGBA Renderer::readImage(Aov aov) const {
  const gl::Texture2D& t = texture(aov);
  return fromGLRows(t.width(), t.height(), t.readRGBA());
}

}  // namespace lgh
