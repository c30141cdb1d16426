#include "bench/common/light_source.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "bench/common/table.h"
#include "render/passes/lgh_build_pass.h"
#include "render/scene/surface_samples.h"

namespace lgh::bench {
namespace {

constexpr float kBoxSize = 10.0f;           // metres, about Sponza's height
constexpr float kTotalIntensity = 1000.0f;  // W/sr per channel over a whole set

}  // namespace

std::filesystem::path defaultBenchScene() {
  return (std::filesystem::path(LGH_SHARED_SCENES_DIR) / "sponza_sun" / "sponza_sun.gltf").lexically_normal();
}

std::filesystem::path chooseRenderScene(const std::string& option, std::string& why) {
  if (!option.empty()) {
    why = "--scene";
    return option;
  }
  if (std::filesystem::exists(defaultBenchScene())) {
    why = "the default scene";
    return defaultBenchScene();
  }
  why = "the project's Cornell box: " + defaultBenchScene().string() + " is not there";
  return std::filesystem::path(LGH_DATA_DIR) / "cornell_box.gltf";
}

LightSource LightSource::onSurfaces(const std::filesystem::path& path) {
  LightSource source;
  source.scene_ = loadScene(path);
  return source;
}

LightSource LightSource::inBox() { return LightSource(); }

std::vector<Light> LightSource::lights(size_t count, std::uint32_t seed) const {
  if (scene_) return sampleSurfaceLights(*scene_, count, seed, kTotalIntensity);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> gaussian;
  const float meanIntensity = kTotalIntensity / float(std::max<size_t>(count, 1));
  std::vector<Light> lights(count);
  for (Light& light : lights) {
    // One draw per statement, so the set does not depend on the compiler's argument order.
    for (int k = 0; k < 3; ++k) light.position[k] = kBoxSize * u(rng);
    for (int k = 0; k < 3; ++k) light.normal[k] = gaussian(rng);  // isotropic direction once normalised
    light.normal = glm::normalize(light.normal);
    for (int k = 0; k < 3; ++k) light.intensity[k] = meanIntensity * 2.0f * u(rng);
  }
  return lights;
}

double LightSource::eMin() const {
  const double diagonal = scene_ ? double(scene_->bounds.diagonal()) : std::sqrt(3.0) * kBoxSize;
  return minTopCellFor(diagonal);
}

std::string LightSource::description() const {
  if (!scene_)
    return "uniform random lights in a " + std::to_string(int(kBoxSize)) + " m cube, random orientations (--random)";
  return "VPL-like: area-uniform points on the surfaces of " + scene_->source.string() + " (" +
         formatCount(scene_->triangleCount()) + " triangles), oriented with the surface";
}

}  // namespace lgh::bench
