#include "render/scene/emitters.h"

#include <algorithm>
#include <cmath>

#include "lgh/light.h"

namespace lgh {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 meanTextureColor(const Scene& scene, int texture) {
  if (texture < 0 || size_t(texture) >= scene.textures.size()) return glm::dvec3(1.0);
  const Texture& t = scene.textures[size_t(texture)];
  glm::dvec3 sum(0.0);
  const size_t n = size_t(t.width) * size_t(t.height);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = t.rgba[4 * i + size_t(c)] / 255.0;  // sRGB-encoded: decode as the shaders do
      sum[c] += v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    }
  return n ? sum / double(n) : glm::dvec3(1.0);
}

void addTriangles(const Scene& scene, std::vector<gpu::GpuEmitter>& out, std::vector<double>& weights,
                  glm::dvec3& total) {
  std::vector<glm::dvec3> textureMean(scene.materials.size(), glm::dvec3(-1.0));
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    const Material& m = scene.materials[scene.triangleMaterials[t]];
    if (!m.isEmissive()) continue;
    glm::dvec3& mean = textureMean[scene.triangleMaterials[t]];
    if (mean.x < 0) mean = meanTextureColor(scene, m.emissiveTexture);
    const glm::vec3 v0 = scene.positions[scene.indices[3 * t]];
    const glm::vec3 e1 = scene.positions[scene.indices[3 * t + 1]] - v0,
                    e2 = scene.positions[scene.indices[3 * t + 2]] - v0;
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(e1), glm::dvec3(e2)));
    const glm::dvec3 power = kPi * area * glm::dvec3(m.emission) * mean;
    if (!(luminance(power) > 0)) continue;  // zero-area or black: never chosen
    gpu::GpuEmitter e{};
    e.kind = gpu::kEmitterTriangle;
    e.v0 = v0;
    e.edge1 = e1;
    e.edge2 = e2;
    e.radiance = m.emission;
    e.light = std::uint32_t(t);
    out.push_back(e);
    weights.push_back(luminance(power));
    total += power;
  }
}

EmitterTable finish(std::vector<gpu::GpuEmitter> emitters, const std::vector<double>& weights, glm::dvec3 total) {
  EmitterTable table;
  double sum = 0;
  for (double w : weights) sum += w;
  double running = 0;
  for (size_t i = 0; i < emitters.size(); ++i) {
    running += weights[i];
    emitters[i].selectionPdf = float(weights[i] / sum);
    emitters[i].cdf = float(running / sum);
  }
  if (!emitters.empty()) emitters.back().cdf = 1.0f;  // no gap at the top from rounding
  table.emitters = std::move(emitters);
  table.totalPower = total;
  return table;
}

}  // namespace

double spotSolidAngleFactor(float innerConeCos, float outerConeCos) {
  const double ci = std::max(innerConeCos, outerConeCos), co = outerConeCos;
  // Inside the inner cone the falloff is 1; between the cones it is t^2 with t linear in cos.
  return 2.0 * kPi * ((1.0 - ci) + (ci - co) / 3.0);
}

glm::dvec3 emitterPower(const PunctualLight& light, const Bounds& sceneBounds) {
  const glm::dvec3 I(light.intensity);
  switch (light.type) {
    case LightType::Point:
      return 4.0 * kPi * I;
    case LightType::Spot:
      return spotSolidAngleFactor(light.innerConeCos, light.outerConeCos) * I;
    case LightType::Directional: {
      const double r = 0.5 * double(sceneBounds.diagonal());
      return kPi * r * r * I;
    }
  }
  return glm::dvec3(0.0);
}

EmitterTable buildEmitterTable(const Scene& scene, const std::vector<PunctualLight>& lights) {
  std::vector<gpu::GpuEmitter> emitters;
  std::vector<double> weights;
  glm::dvec3 total(0.0);
  for (size_t i = 0; i < lights.size(); ++i) {
    const glm::dvec3 power = emitterPower(lights[i], scene.bounds);
    if (!(luminance(power) > 0)) continue;
    gpu::GpuEmitter e{};
    e.kind = gpu::kEmitterPunctual;
    e.light = std::uint32_t(i);
    emitters.push_back(e);
    weights.push_back(luminance(power));
    total += power;
  }
  addTriangles(scene, emitters, weights, total);
  return finish(std::move(emitters), weights, total);
}

EmitterTable buildEmissiveTriangleTable(const Scene& scene) {
  std::vector<gpu::GpuEmitter> emitters;
  std::vector<double> weights;
  glm::dvec3 total(0.0);
  addTriangles(scene, emitters, weights, total);
  return finish(std::move(emitters), weights, total);
}

}  // namespace lgh
