#include "bench/sweep_reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

namespace lgh::bench {
namespace {

namespace fs = std::filesystem;

// The fraction of the pixels to compute, rounded so that it makes a stable cache key.
double pixelFraction(const reference::ReferenceInput& input, const ReferenceRequest& request) {
  size_t valid = 0;
  for (const glm::vec4& p : input.position) valid += p.w > 0 ? 1 : 0;
  const double pairs = double(valid) * double(input.lights.size());
  double fraction =
      request.pixels > 0 ? std::min(request.pixels, 1.0) : (pairs <= request.budget ? 1.0 : request.budget / pairs);
  if (fraction < 1.0) fraction = std::max(1e-4, std::round(fraction * 1e4) / 1e4);
  return fraction;
}

// Everything the reference depends on.
std::string cacheKey(const SceneSpec& scene, const RenderSettings& s, const reference::ReferenceInput& input,
                     double fraction) {
  std::error_code error;
  const auto mtime = fs::last_write_time(scene.path, error).time_since_epoch().count();
  const std::uint64_t gbuffer =
      reference::hashBytes(input.normal.data(), input.normal.size() * sizeof(glm::vec4),
                           reference::hashBytes(input.position.data(), input.position.size() * sizeof(glm::vec4)));
  const InputLightSettings& l = s.inputLights;
  std::ostringstream key;
  key << "lgh reference v1\nscene " << scene.path.string() << " mtime " << mtime << " bytes "
      << fs::file_size(scene.path, error) << "\ncamera '" << s.image.camera << "' " << s.image.width << "x"
      << s.image.height << "\nlights vpls " << l.vpls << " bounces " << l.bounces << " emitter-samples "
      << l.emitterSamples << " max-direct-lights " << l.maxDirectLights << " seed " << l.seed << " count "
      << input.lights.size() << " hash " << reference::hex64(reference::hashLights(input.lights)) << "\ngbuffer "
      << reference::hex64(gbuffer) << "\nclamp " << std::hexfloat << input.clampDistance << std::defaultfloat
      << "\npixels fraction " << fraction << " seed 1\nshadowed 1\n";
  return key.str();
}

}  // namespace

reference::ReferenceImage obtainReference(const reference::OcclusionScene& occlusion, const SceneSpec& scene,
                                          const Renderer& renderer, const std::vector<Light>& lights,
                                          const ReferenceRequest& request, ReferenceInfo& info) {
  const RenderSettings& s = renderer.settings();
  reference::ReferenceInput input;
  input.width = s.image.width;
  input.height = s.image.height;
  input.position = renderer.readImage(Aov::Position).pixels;
  input.normal = renderer.readImage(Aov::Normal).pixels;
  input.lights = lights;
  input.clampDistance = renderer.clampDistance();
  const double fraction = pixelFraction(input, request);
  const std::string key = cacheKey(scene, s, input, fraction);
  info.fraction = fraction;
  info.imagePixels = size_t(s.image.width) * size_t(s.image.height);
  std::optional<reference::ReferenceImage> ref;
  if (!request.cacheDir.empty()) {
    ref = reference::loadReference(request.cacheDir, key);
    info.cacheFile = (request.cacheDir / reference::cacheFileName(key)).string();
  }
  info.cached = bool(ref);
  if (!ref) {
    reference::ReferenceOptions o;
    o.pixelFraction = fraction;
    o.threads = request.threads;
    o.label = request.label;
    ref = reference::computeReference(occlusion, input, o);
    if (!request.cacheDir.empty()) reference::storeReference(request.cacheDir, key, *ref);
  }
  info.pixels = ref->pixels.size();
  info.seconds = ref->seconds;
  info.rays = ref->rays;
  info.pairs = ref->pairs;
  info.threads = ref->threads;
  return std::move(*ref);
}

}  // namespace lgh::bench
