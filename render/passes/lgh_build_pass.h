#pragma once
// Builds the lighting grid hierarchy on the GPU (Lin & Yuksel 2019, Sec. 3.1; docs/design.md §2).
//   in:  input lights S0 (GpuLight buffer), options
//   out: GpuHierarchy: every level's grid lights merged into one buffer, with per-level offsets
//
// Steps (each a profiler scope, so per-step times come out as in the paper's Table 1):
//   bounds        reduce the lights' bounds, the brightest light and the lit count
//   level count   the paper's rule, largest L with |S1| < N/2 (only when levels are automatic)
//   S1            insert vertex keys, compact (prefix sum), scatter S0 with atomics, finalise
//   S2..SL        gather from the level below without atomics (or, in the reference build,
//                 scatter S0 into every level, as S1)
//   merge         copy the levels into one buffer for a single instanced draw
// Memory follows occupied vertices: each level is a hash table of the vertices lights touch, sized by
// the light count, never a dense grid (which would grow as 8^L).

#include <algorithm>
#include <vector>

#include "lgh/grid.h"
#include "lgh/hierarchy.h"
#include "lgh/light.h"
#include "render/gl/buffer.h"
#include "render/gl/prefix_sum.h"
#include "render/gl/profiler.h"
#include "render/gl/program.h"
#include "render/pass_names.h"
#include "shared/lgh_types.h"

namespace lgh {

struct LghBuildOptions {
  int levels = 0;                  // 0: automatic (the paper's rule); else 1..LghBuildPass::kMaxLevels
  bool gatherCoarseLevels = true;  // false: scatter S0 into every level (the reference build)
  bool floatAtomics = false;       // S1 sums in float atomics (GL_NV_shader_atomic_float) instead of 64-bit fixed point
  double eMin = 0.0;               // smallest top-cell edge (one light, coincident lights); <= 0 means 1
  size_t maxLightsPerDispatch = 0;  // 0: as many as one storage block holds; tests set it small to exercise chunking
};

// The smallest top-cell edge e_min for a scene of this diagonal: 1e-4 of it, so that one light, or
// lights that coincide, still get a grid at the scene's scale.
inline double minTopCellFor(double sceneDiagonal) { return 1e-4 * std::max(sceneDiagonal, 1e-6); }

struct LghLevelRange {
  size_t offset = 0, count = 0;  // into GpuHierarchy::gridLights, in grid lights
};

// A level's vertex lookup: hash table of vertex keys (lgh_grid.glsl) and, per slot, the grid light's
// index within the level. Kept after the build for passes that find grid lights from positions.
struct LghLevelLookup {
  gl::Buffer keys, slotIndex;
  size_t capacity = 0;  // slots, a power of two
};

struct GpuHierarchy {
  GridGeometry grid;                    // levels == 0 when there is nothing to build (no lights)
  std::vector<LghLevelRange> levels;    // levels[l] for l in 1..L; levels[0] unused
  std::vector<LghLevelLookup> lookups;  // lookups[l] for l in 1..L
  bool gathered = true;                 // levels >= 2 built from the level below (else each from S0)
  gl::Buffer gridLights;                // gpu::GpuGridLight, level 1 first
  size_t gridLightCount = 0;
  size_t litLightCount = 0;  // input lights with luminance > 0
  // Reads level l back, for tests and statistics.
  std::vector<gpu::GpuGridLight> downloadLevel(int level) const;
};

// Input lights per dispatch when S0 is bound in chunks of at most one storage block (and at most
// `requested` lights, 0: no limit): a multiple of 1024 lights, so every chunk's byte offset is a
// multiple of 32 KiB, which satisfies any SSBO offset alignment.
size_t lightChunkSize(size_t maxBlockBytes, size_t requested = 0);

// The build kernels' grid uniforms for `level` (and any pass that locates cells the same way).
gpu::LghGridParams gridParamsFor(const GridGeometry& grid, int level, size_t tableCapacity);

class LghBuildPass {
 public:
  static constexpr int kMaxLevels = int(gpu::kMaxBuildLevels);

  explicit LghBuildPass(bool floatAtomicsAvailable);
  bool floatAtomicsAvailable() const { return floatAtomicsAvailable_; }

  // Throws std::runtime_error for impossible requests (levels out of range, float atomics without the
  // extension, a level too large for one storage block), naming the limit.
  void execute(const gl::Buffer& lights, size_t lightCount, const LghBuildOptions& options, GpuHierarchy& out,
               gl::Profiler* profiler = nullptr);

 private:
  struct LevelTable {                         // the occupied vertices of one level
    gl::Buffer keys, slotIndex, compactKeys;  // lookup: hash table, slot -> light index, light -> key
    gl::Buffer gridLights;                    // the level's grid lights, until merged
    size_t capacity = 0, count = 0;
    void releaseCompactKeys() { compactKeys = {}; }
  };
  struct Bounds {
    glm::dvec3 lower, upper;
    double largestValue = 0;
    size_t litCount = 0;
  };

  Bounds computeBounds(const gl::Buffer& lights, size_t lightCount);
  // Moves a finished level's lookup into a table fitted to its occupied vertices (about 2 x count slots),
  // when the build's table is larger (it needs the level's compact keys).
  void fitLookup(LevelTable& table, const GridGeometry& grid, int level);
  int chooseLevelCount(const gl::Buffer& lights, size_t lightCount, const Bounds& bounds, double eMin);
  size_t countFinestVertices(const gl::Buffer& lights, size_t lightCount, const GridGeometry& grid, size_t stopAt);
  void insertKeys(const gl::Buffer& sources, size_t sourceCount, bool fromGridLights, LevelTable& table, int level,
                  const GridGeometry& grid, size_t expectedKeys, size_t stopAt);
  void compact(LevelTable& table);
  void scatterLevel(const gl::Buffer& lights, size_t lightCount, const GridGeometry& grid, int level, double largest,
                    bool floatAtomics, LevelTable& table);
  void gatherLevel(const LevelTable& children, const GridGeometry& grid, int level, LevelTable& table);
  void setGridParams(const GridGeometry& grid, int level, size_t capacity, size_t stopAt, double scale);
  // Runs fn(offsetInLights, countInChunk) with the lights bound at LGH_BINDING_PASS0 chunk by chunk.
  template <typename Fn>
  void forEachLightChunk(const gl::Buffer& lights, size_t lightCount, Fn&& fn);

  bool floatAtomicsAvailable_;
  size_t maxBlockBytes_;
  size_t maxLightsPerDispatch_ = 0;
  gl::Program bounds_, insertFromLights_, insertFromGridLights_, compactFlags_, compactWrite_, scatterFixed_,
      finalizeFixed_, gather_;
  gl::Program scatterFloat_, finalizeFloat_;  // only with GL_NV_shader_atomic_float
  gl::Program fitInsert_, fitIndex_;
  gl::PrefixSum prefixSum_{passes::kLghBuild};
  gl::Buffer gridParams_, counters_, boundsResult_;
  gl::Buffer accPosition_, accIntensity_, accNormal_;
};

// Conversions between the library's lights and the GPU's (octahedral normals). fromGpuLights returns
// what the GPU sees, decoded normals included, so CPU references built from it match bit for bit.
std::vector<gpu::GpuLight> toGpuLights(const std::vector<Light>& lights);
std::vector<Light> fromGpuLights(const std::vector<gpu::GpuLight>& lights);

}  // namespace lgh
