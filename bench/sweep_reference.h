#pragma once
// The sweep's exact reference for a case (bench/reference.h: Embree on the CPU), from a disk cache
// keyed by everything it depends on (scene file, camera, size, light settings and S0's hash, the
// G-buffer's hash, d_c, the pixel subset), computed and stored there when missing.

#include <filesystem>
#include <string>
#include <vector>

#include "bench/reference.h"
#include "bench/sweep_case.h"
#include "render/renderer.h"

namespace lgh::bench {

struct ReferenceRequest {
  double pixels = 0;               // pixel fraction; 0: automatic, all pixels unless that exceeds `budget` pairs
  double budget = 1.6e9;           // pixel-light pairs of a full-image reference before subsetting
  unsigned threads = 0;            // workers (0: one per hardware thread)
  std::filesystem::path cacheDir;  // empty: no cache
  std::string label;               // for the progress bar
};

// The reference for the renderer's last frame (its G-buffer, settings and d_c) lit by `lights` (its
// S0); fills info with how it was obtained.
reference::ReferenceImage obtainReference(const reference::OcclusionScene& occlusion, const SceneSpec& scene,
                                          const Renderer& renderer, const std::vector<Light>& lights,
                                          const ReferenceRequest& request, ReferenceInfo& info);

}  // namespace lgh::bench
