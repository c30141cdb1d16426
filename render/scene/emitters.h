#pragma once
// The scene's light sources as emitters of light paths, each with its emitted power (flux), so VPL
// generation can choose them with probability proportional to power (by luminance).
//
//   point        4 pi I
//   spot         2 pi I [(1 - cos_inner) + (cos_inner - cos_outer) / 3]   (glTF's squared ramp)
//   directional  E pi r^2, over a disk covering the scene's bounding sphere (radius r)
//   triangle     pi L A   (one-sided Lambertian emitter, L = emission x mean of the emissive texture)

#include <glm/glm.hpp>
#include <vector>

#include "render/scene/scene.h"
#include "shared/scene_types.h"

namespace lgh {

struct EmitterTable {
  std::vector<gpu::GpuEmitter> emitters;  // cdf and selectionPdf filled, by luminance of power
  glm::dvec3 totalPower{0.0};             // RGB watts of everything in the table
  bool empty() const { return emitters.empty(); }
};

// Spot and glTF falloff integral: the spot's flux divided by its intensity.
double spotSolidAngleFactor(float innerConeCos, float outerConeCos);

glm::dvec3 emitterPower(const PunctualLight& light, const Bounds& sceneBounds);

// All light sources: punctual lights first (in scene order), then emissive triangles. `lights` stands
// in for scene.lights when they have been changed since loading (SceneGpu::lights()).
EmitterTable buildEmitterTable(const Scene& scene, const std::vector<PunctualLight>& lights);
inline EmitterTable buildEmitterTable(const Scene& scene) { return buildEmitterTable(scene, scene.lights); }
// Emissive triangles only (for sampling them as direct lights).
EmitterTable buildEmissiveTriangleTable(const Scene& scene);

}  // namespace lgh
