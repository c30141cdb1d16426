#include "bench/sweep/sweep_reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "bench/common/ranks.h"

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

// Everything the reference depends on, by content (so that every host of a cluster, and a copy of the
// scene elsewhere, names it alike): the occluders' triangles, the camera and size, the light settings and
// S0's hash, the G-buffer's hash, d_c, the pixel subset.
std::string cacheKey(const reference::OcclusionScene& occlusion, const SceneSpec& scene, const RenderSettings& s,
                     const reference::ReferenceInput& input, double fraction) {
  const std::uint64_t gbuffer =
      reference::hashBytes(input.normal.data(), input.normal.size() * sizeof(glm::vec4),
                           reference::hashBytes(input.position.data(), input.position.size() * sizeof(glm::vec4)));
  const InputLightSettings& l = s.inputLights;
  std::ostringstream key;
  key << "lgh reference v2\nscene " << scene.path.filename().string() << " triangles "
      << reference::hex64(occlusion.contentHash()) << "\ncamera '" << s.image.camera << "' " << s.image.width << "x"
      << s.image.height << "\nlights vpls " << l.vpls << " bounces " << l.bounces << " emitter-samples "
      << l.emitterSamples << " max-direct-lights " << l.maxDirectLights << " seed " << l.seed << " count "
      << input.lights.size() << " hash " << reference::hex64(reference::hashLights(input.lights)) << "\ngbuffer "
      << reference::hex64(gbuffer) << "\nclamp " << std::hexfloat << input.clampDistance << std::defaultfloat
      << "\npixels fraction " << fraction << " seed 1\nshadowed 1\n";
  return key.str();
}

}  // namespace

fs::path defaultReferenceCache() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  return (error ? fs::current_path() : exe.parent_path()) / "reference-cache";
}

reference::ReferenceInput referenceInput(const Renderer& renderer, const std::vector<Light>& lights) {
  const RenderSettings& s = renderer.settings();
  reference::ReferenceInput input;
  input.width = s.image.width;
  input.height = s.image.height;
  input.position = renderer.readImage(Aov::Position).pixels;
  input.normal = renderer.readImage(Aov::Normal).pixels;
  input.lights = lights;
  input.clampDistance = renderer.clampDistance();
  return input;
}

reference::ReferenceImage obtainReference(const Ranks& ranks, const reference::OcclusionScene& occlusion,
                                          const SceneSpec& scene, const RenderSettings& settings,
                                          const reference::ReferenceInput& input, const ReferenceRequest& request,
                                          ReferenceInfo& info, TileCounts* tiles) {
  // The subset and the key are rank 0's; computeTiledReference sends them. A rank that rendered the frame
  // too (the sweep's ranks measure against this reference) must have rendered rank 0's: the same key.
  const bool given = !input.position.empty();
  const double fraction = given ? pixelFraction(input, request) : 1.0;
  const std::string key = given ? cacheKey(occlusion, scene, settings, input, fraction) : std::string();
  std::string rootKey = key;
  ranks.broadcast(rootKey);
  if (given && key != rootKey)
    ranks.abort(
        "reference: this rank rendered another frame than rank 0 (its G-buffer, lights or settings differ; "
        "its errors would be against another frame's reference). Its key:\n" +
        key + "rank 0's:\n" + rootKey);
  std::vector<std::uint32_t> pixels;
  if (ranks.root()) {
    pixels = reference::choosePixels(input.width, input.height, fraction, 1);
    if (!request.run.cacheDir.empty()) info.cacheFile = (request.run.cacheDir / reference::cacheFileName(key)).string();
  }
  TileCounts counts;
  reference::ReferenceImage ref = computeTiledReference(ranks, occlusion, input, pixels, key, request.run, counts);
  info.cached = counts.fromCache;
  if (tiles) *tiles = counts;
  info.imagePixels = size_t(ref.width) * size_t(ref.height);
  info.fraction = double(ref.pixels.size()) / double(std::max<size_t>(info.imagePixels, 1));
  if (ranks.root()) info.fraction = fraction;  // the rounded fraction the key names
  info.pixels = ref.pixels.size();
  info.seconds = ref.seconds;
  info.rays = ref.rays;
  info.pairs = ref.pairs;
  info.threads = ref.threads;
  return ref;
}

}  // namespace lgh::bench
