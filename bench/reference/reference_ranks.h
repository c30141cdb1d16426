#pragma once
// The exact reference computed by every rank of the run together (bench/common/ranks.h: MPI, or one process),
// in tiles that outlive the run (bench/reference/reference_tiles.h). Rank 0 holds the input (its G-buffer and S0)
// and the cache key; it finds the tiles already in the cache, and every rank receives the input and
// computes the missing tiles dealt to it (interleaved: tile i of the missing ones to rank i mod N, so
// that each rank gets tiles from all over the image), with its own Embree workers, storing each tile as
// it completes. Rank 0 gathers the parts, assembles the image (the same pixels, sums and order as one
// process computing it, bit for bit: each pixel's sums depend on that pixel alone), stores it in the
// cache and removes the tiles; every rank gets the image.
//
// A rank that fails on a tile ends the whole run with a message naming the rank and the tile
// (Ranks::abort: MPI_Abort), never a hang.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/reference/reference.h"
#include "bench/reference/reference_tiles.h"

namespace lgh::bench {

class Ranks;

struct TiledReferenceOptions {
  int tileSize = 32;
  unsigned threads = 0;            // Embree workers per rank (0: this host's hardware threads / its ranks)
  std::filesystem::path cacheDir;  // empty: no cache, no tiles kept (the parts travel by MPI only)
  std::string label = "reference";
  bool progress = true;  // rank 0's progress on stderr
  // Test hooks (hidden options of lgh-bench reference): the process kills itself (SIGKILL) once it has
  // stored this many tiles; the tile whose computation throws.
  int killAfterTiles = -1;
  int failTile = -1;
};

// What happened to the tiles (all ranks together).
struct TileCounts {
  int tiles = 0;     // of the image
  int cached = 0;    // whole files of an earlier run, used
  int computed = 0;  // computed by this run
  int ranks = 1;
  bool fromCache = false;  // the whole reference was in the cache: no tile computed or read
  unsigned threadsPerRank = 0;
  double seconds = 0;                  // wall time of the computed tiles
  std::vector<std::string> redoneWhy;  // the computed tiles whose file was truncated, corrupt or another's
};

// Collective: every rank calls it. `input`, `pixels` (ascending, the subset) and `description` (the
// cache key) are read on rank 0 only. If the whole reference is in the cache, it is loaded (no tile is
// computed). Returns the reference on every rank.
reference::ReferenceImage computeTiledReference(const Ranks& ranks, const reference::OcclusionScene& occlusion,
                                                const reference::ReferenceInput& input,
                                                const std::vector<std::uint32_t>& pixels,
                                                const std::string& description, const TiledReferenceOptions& options,
                                                TileCounts& counts);

}  // namespace lgh::bench
