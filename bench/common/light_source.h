#pragma once
// Where the benchmarks' input lights S0 come from: VPL-like lights on a scene's surfaces (Sponza by
// default, as the paper's Figure 5 scene), or, without a scene, lights uniform in a box.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lgh/light.h"
#include "render/scene/scene.h"

namespace lgh::bench {

// The scene the benchmarks use when none is named, if ../shared/scenes is beside the checkout.
std::filesystem::path defaultBenchScene();
// The scene a rendering benchmark uses: `option` if given, else the default scene if it is there, else
// the project's Cornell box; `why` says which and why, for the output.
std::filesystem::path chooseRenderScene(const std::string& option, std::string& why);

class LightSource {
 public:
  // Lights on the surfaces of the glTF scene at `path` (throws SceneLoadError if it cannot be loaded).
  static LightSource onSurfaces(const std::filesystem::path& path);
  // Lights uniform in a 10 m cube, with random orientations.
  static LightSource inBox();

  // `count` lights; the same count and seed give the same set. Every set carries the same total
  // intensity, so sets of different sizes light the scene alike (as VPLs from one light would).
  std::vector<Light> lights(size_t count, std::uint32_t seed) const;
  // The build's smallest top-cell edge: 1e-4 of the region's diagonal (docs/design.md §2).
  double eMin() const;
  // One line for the output, e.g. "VPL-like: points on the surfaces of sponza_sun.gltf (66,447 triangles)".
  std::string description() const;

 private:
  std::optional<Scene> scene_;  // none: the box
};

}  // namespace lgh::bench
