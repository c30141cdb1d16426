#pragma once
// VPL-like light sets on a scene's surfaces, for benchmarks and tests that need lights distributed the
// way VPLs are (on walls and floors, oriented, dense where the geometry is) without tracing paths.

#include <cstdint>
#include <vector>

#include "lgh/light.h"
#include "render/scene/scene.h"

namespace lgh {

// `count` oriented (cosine) lights at points drawn uniformly over the scene's surface area: a triangle
// with probability proportional to its area, then a uniform point on it. Each light's normal is the
// triangle's geometric normal, flipped to the side of its vertex normals (so it faces where the mesh
// says the surface faces). Intensity: every channel of every light is (totalIntensity / count) * u with
// u uniform in [0, 2): random colours whose expected sum per channel over the set is totalIntensity.
// Deterministic for a given seed. Zero-area triangles are never picked; throws std::invalid_argument
// when the scene has no surface area at all.
std::vector<Light> sampleSurfaceLights(const Scene& scene, size_t count, std::uint32_t seed, float totalIntensity);

}  // namespace lgh
