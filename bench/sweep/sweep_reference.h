#pragma once
// The exact reference for a renderer's frame (bench/reference/reference.h: Embree on the CPU), from a disk cache
// keyed by everything it depends on (the occluders' triangles, camera, size, light settings and S0's
// hash, the G-buffer's hash, d_c, the pixel subset), computed by every rank of the run in resumable
// tiles (bench/reference/reference_ranks.h) and stored there when missing. lgh-bench sweep and lgh-bench
// reference both come here, so a reference made by one is found by the other.

#include <filesystem>
#include <string>
#include <vector>

#include "bench/reference/reference.h"
#include "bench/reference/reference_ranks.h"
#include "bench/sweep/sweep_case.h"
#include "render/renderer.h"

namespace lgh::bench {

struct ReferenceRequest {
  double pixels = 0;          // pixel fraction; 0: automatic, all pixels unless that exceeds `budget` pairs
  double budget = 1.6e9;      // pixel-light pairs of a full-image reference before subsetting
  TiledReferenceOptions run;  // tiles, threads, cache (empty: none), label, test hooks
};

// The cache both use by default: reference-cache beside the lgh-bench executable.
std::filesystem::path defaultReferenceCache();

// Rank 0's frame as the reference sees it: the renderer's G-buffer and d_c, lit by `lights` (its S0).
reference::ReferenceInput referenceInput(const Renderer& renderer, const std::vector<Light>& lights);

// Collective (every rank calls it): the reference for rank 0's `input`, rendered with `settings`, on
// every rank; fills info (and *tiles) with how it was obtained. Another rank may pass an empty input
// (lgh-bench reference's do: they render nothing); one that passes its own must have rendered rank 0's
// frame (the same key), or the run ends saying so.
reference::ReferenceImage obtainReference(const Ranks& ranks, const reference::OcclusionScene& occlusion,
                                          const SceneSpec& scene, const RenderSettings& settings,
                                          const reference::ReferenceInput& input, const ReferenceRequest& request,
                                          ReferenceInfo& info, TileCounts* tiles = nullptr);

}  // namespace lgh::bench
