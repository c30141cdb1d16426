#include "render/scene/surface_samples.h"

#include <algorithm>
#include <random>
#include <stdexcept>

namespace lgh {

std::vector<Light> sampleSurfaceLights(const Scene& scene, size_t count, std::uint32_t seed, float totalIntensity) {
  auto corner = [&](size_t triangle, int k) { return scene.indices[3 * triangle + size_t(k)]; };
  auto edgeCross = [&](size_t triangle) {
    const glm::vec3 a = scene.positions[corner(triangle, 0)];
    return glm::cross(scene.positions[corner(triangle, 1)] - a, scene.positions[corner(triangle, 2)] - a);
  };

  // Cumulative area (x2) per triangle: a sample x in [0, total) picks the first triangle whose
  // cumulative area exceeds x (upper_bound), which can never be a zero-area one.
  std::vector<double> cumulativeArea(scene.triangleCount());
  double total = 0;
  for (size_t t = 0; t < cumulativeArea.size(); ++t) cumulativeArea[t] = total += glm::length(edgeCross(t));
  if (count > 0 && !(total > 0))
    throw std::invalid_argument("sampleSurfaceLights: " + scene.source.string() + " has no surface area to sample");

  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const float meanIntensity = totalIntensity / float(std::max<size_t>(count, 1));
  const bool hasVertexNormals = scene.normals.size() == scene.positions.size();
  std::vector<Light> lights(count);
  for (Light& light : lights) {
    const size_t t =
        size_t(std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), u(rng) * total) - cumulativeArea.begin());
    const size_t triangle = std::min(t, cumulativeArea.size() - 1);  // guards u * total rounding up to total
    // Uniform point on the triangle: fold the unit square's upper half back onto the lower one.
    double s = u(rng), r = u(rng);
    if (s + r > 1) s = 1 - s, r = 1 - r;
    const glm::vec3 a = scene.positions[corner(triangle, 0)], b = scene.positions[corner(triangle, 1)],
                    c = scene.positions[corner(triangle, 2)];
    light.position = a + float(s) * (b - a) + float(r) * (c - a);

    glm::vec3 normal = glm::normalize(edgeCross(triangle));
    if (hasVertexNormals) {
      const glm::vec3 vertexNormals =
          scene.normals[corner(triangle, 0)] + scene.normals[corner(triangle, 1)] + scene.normals[corner(triangle, 2)];
      if (glm::dot(normal, vertexNormals) < 0) normal = -normal;
    }
    light.normal = normal;
    // One draw per statement: the order of draws (hence the set) must not depend on the compiler.
    for (int k = 0; k < 3; ++k) light.intensity[k] = meanIntensity * 2.0f * float(u(rng));
  }
  return lights;
}

}  // namespace lgh
