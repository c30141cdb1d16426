#include "render/passes/lgh_build_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/octahedral.h"

namespace lgh {
namespace {

constexpr unsigned kLocalSize = 256;
constexpr double kFixedPointHeadroom = 4611686018427387904.0;  // 2^62: sums stay below 2^63
// What the hierarchy's memory follows (gl::Label::scaledBy): occupied vertices, never the grid's extent.
constexpr const char* kOccupied = "the occupied grid vertices (vpls, levels)";

size_t nextPowerOfTwo(size_t v) {
  size_t p = 1;
  while (p < v) p <<= 1;
  return p;
}

size_t verticesPerAxis(const GridGeometry& grid, int level) { return size_t(grid.cellsPerAxis(level)) + 1; }
size_t denseVertexCount(const GridGeometry& grid, int level) {
  const size_t n = verticesPerAxis(grid, level);
  return n * n * n;
}

std::string mib(size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::vector<gpu::GpuGridLight> GpuHierarchy::downloadLevel(int level) const {
  if (level < 1 || size_t(level) >= levels.size()) return {};
  return gridLights.download<gpu::GpuGridLight>(levels[size_t(level)].count, levels[size_t(level)].offset);
}

LghBuildPass::LghBuildPass(bool floatAtomicsAvailable)
    : floatAtomicsAvailable_(floatAtomicsAvailable),
      bounds_(gl::Program::compute("lgh_bounds.comp")),
      insertFromLights_(gl::Program::compute("lgh_insert_keys.comp")),
      insertFromGridLights_(gl::Program::compute("lgh_insert_keys.comp", {{"LGH_FROM_GRID_LIGHTS", "1"}})),
      compactFlags_(gl::Program::compute("lgh_compact.comp", {{"LGH_COMPACT_FLAGS", "1"}})),
      compactWrite_(gl::Program::compute("lgh_compact.comp")),
      scatterFixed_(gl::Program::compute("lgh_scatter.comp")),
      finalizeFixed_(gl::Program::compute("lgh_finalize.comp")),
      gather_(gl::Program::compute("lgh_gather.comp")),
      fitInsert_(gl::Program::compute("lgh_fit_table.comp", {{"LGH_FIT_INSERT", "1"}})),
      fitIndex_(gl::Program::compute("lgh_fit_table.comp")) {
  if (floatAtomicsAvailable_) {
    scatterFloat_ = gl::Program::compute("lgh_scatter.comp", {{"LGH_FLOAT_ATOMICS", "1"}});
    finalizeFloat_ = gl::Program::compute("lgh_finalize.comp", {{"LGH_FLOAT_ATOMICS", "1"}});
  }
  maxBlockBytes_ = std::max(gl::maxStorageBlockBytes(), gl::kMinStorageBlockBytes);
}

template <typename Fn>
void LghBuildPass::forEachLightChunk(const gl::Buffer& lights, size_t lightCount, Fn&& fn) {
  const size_t chunk = lightChunkSize(maxBlockBytes_, maxLightsPerDispatch_);
  for (size_t first = 0; first < lightCount; first += chunk) {
    const size_t count = std::min(chunk, lightCount - first);
    lights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, first * sizeof(gpu::GpuLight),
                     count * sizeof(gpu::GpuLight));
    fn(first, count);
  }
}

size_t lightChunkSize(size_t maxBlockBytes, size_t requested) {
  constexpr size_t kGranularity = 1024;
  const size_t blockLights = maxBlockBytes / sizeof(gpu::GpuLight);
  const size_t chunk = requested ? std::min(requested, blockLights) : blockLights;
  return std::max(kGranularity, chunk / kGranularity * kGranularity);
}

gpu::LghGridParams gridParamsFor(const GridGeometry& grid, int level, size_t tableCapacity) {
  gpu::LghGridParams p{};
  p.originAndTopCell = glm::vec4(glm::vec3(grid.origin), float(grid.topCellSize));
  p.levelsAndCounts = glm::uvec4(unsigned(grid.levels), unsigned(level), 0u, unsigned(verticesPerAxis(grid, level)));
  p.cellSizeAndScale = glm::vec4(float(grid.cellSize(level)), 0.0f, 0.0f, 0.0f);
  p.table = glm::uvec4(unsigned(tableCapacity), unsigned(tableCapacity - 1), 0xffffffffu, 0u);
  return p;
}

void LghBuildPass::setGridParams(const GridGeometry& grid, int level, size_t capacity, size_t stopAt, double scale) {
  gpu::LghGridParams p = gridParamsFor(grid, level, capacity);
  p.cellSizeAndScale.y = float(scale);
  p.table.z = unsigned(std::min<size_t>(stopAt, 0xffffffffu));
  gridParams_.update(&p, sizeof p);
  gridParams_.bindBase(GL_UNIFORM_BUFFER, LGH_UBO_PASS);
}

LghBuildPass::Bounds LghBuildPass::computeBounds(const gl::Buffer& lights, size_t lightCount) {
  // Start values: lower bounds at the largest ordered bits (0xffffffff), upper bounds and counts at 0.
  gpu::LghBoundsResult init{};
  for (int a = 0; a < 3; ++a) init.litLower[a] = init.allLower[a] = 0xffffffffu;
  boundsResult_.update(&init, sizeof init);
  boundsResult_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  forEachLightChunk(lights, lightCount, [&](size_t, size_t count) {
    bounds_.set("lightCount", GLuint(count));
    bounds_.dispatch1D(count, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  });
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const gpu::LghBoundsResult r = boundsResult_.download<gpu::LghBoundsResult>(1)[0];
  Bounds b;
  b.litCount = r.litCount;
  const bool lit = b.litCount > 0;  // no lit light: fall back to all lights, as lgh::makeGrid does
  for (int a = 0; a < 3; ++a) {
    b.lower[a] = gpu::fromOrderedBits(lit ? r.litLower[a] : r.allLower[a]);
    b.upper[a] = gpu::fromOrderedBits(lit ? r.litUpper[a] : r.allUpper[a]);
  }
  b.largestValue = gpu::fromOrderedBits(r.largestValue);
  return b;
}

void LghBuildPass::insertKeys(const gl::Buffer& sources, size_t sourceCount, bool fromGridLights, LevelTable& table,
                              int level, const GridGeometry& grid, size_t expectedKeys, size_t stopAt) {
  const size_t maxCapacity = nextPowerOfTwo(maxBlockBytes_ / sizeof(GLuint) + 1) / 2;
  size_t capacity = nextPowerOfTwo(std::max<size_t>(1024, 2 * std::min(expectedKeys, denseVertexCount(grid, level))));
  for (;;) {
    if (capacity > maxCapacity)
      throw std::runtime_error("LGH build: level " + std::to_string(level) + " needs more occupied vertices than a " +
                               mib(maxBlockBytes_) + " storage block holds; use fewer levels");
    ensureSize(table.keys, {passes::kLghBuild, "vertex hash tables", kOccupied}, capacity * sizeof(GLuint));
    table.keys.clearUint(gpu::kEmptyKey);
    table.capacity = capacity;
    counters_.clear();
    setGridParams(grid, level, capacity, stopAt, 0.0);
    table.keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
    counters_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
    const gl::Program& program = fromGridLights ? insertFromGridLights_ : insertFromLights_;
    if (fromGridLights) {
      sources.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
      program.set("sourceCount", GLuint(sourceCount));
      program.dispatch1D(sourceCount, kLocalSize);
    } else {
      forEachLightChunk(sources, sourceCount, [&](size_t, size_t count) {
        program.set("sourceCount", GLuint(count));
        program.dispatch1D(count, kLocalSize);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      });
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    const auto c = counters_.download<GLuint>(2);
    table.count = c[0];
    // Keep the load factor at most 1/2 (short probe sequences); a full table lost keys: retry larger.
    if (c[1] == 0 && 2 * table.count <= capacity) return;
    if (table.count >= stopAt) return;  // a level-count trial that already has its answer
    capacity = nextPowerOfTwo(4 * std::max<size_t>(table.count, capacity / 2));
  }
}

void LghBuildPass::compact(LevelTable& table) {
  ensureSize(table.slotIndex, {passes::kLghBuild, "slot indices", kOccupied}, table.capacity * sizeof(GLuint));
  table.keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  table.slotIndex.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  compactFlags_.set("capacity", GLuint(table.capacity));
  compactFlags_.dispatch1D(table.capacity, kLocalSize);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  table.count = prefixSum_.scan(table.slotIndex, table.capacity);
  ensureSize(table.compactKeys, {passes::kLghBuild, "compact keys", kOccupied},
             std::max<size_t>(table.count, 1) * sizeof(GLuint));
  table.keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  table.slotIndex.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  table.compactKeys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS7);
  compactWrite_.set("capacity", GLuint(table.capacity));
  compactWrite_.dispatch1D(table.capacity, kLocalSize);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  const size_t bytes = table.count * sizeof(gpu::GpuGridLight);
  if (bytes > maxBlockBytes_)
    throw std::runtime_error("LGH build: " + std::to_string(table.count) + " grid lights in one level exceed a " +
                             mib(maxBlockBytes_) + " storage block; use fewer levels");
  ensureSize(table.gridLights, {passes::kLghBuild, "grid lights of a level", kOccupied},
             std::max<size_t>(bytes, sizeof(gpu::GpuGridLight)));
}

void LghBuildPass::scatterLevel(const gl::Buffer& lights, size_t lightCount, const GridGeometry& grid, int level,
                                double largest, bool floatAtomics, LevelTable& table) {
  insertKeys(lights, lightCount, false, table, level, grid, 2 * lightCount, SIZE_MAX);
  compact(table);
  // Accumulators: 6 + 3 + 4 values per vertex, two words each in fixed point.
  const size_t words = floatAtomics ? 1 : 2;
  for (auto [buffer, values] : {std::pair{&accPosition_, 6}, {&accIntensity_, 3}, {&accNormal_, 4}}) {
    const size_t bytes = std::max<size_t>(table.count, 1) * size_t(values) * words * sizeof(GLuint);
    if (bytes > maxBlockBytes_)
      throw std::runtime_error("LGH build: the sums of " + std::to_string(table.count) +
                               " vertices exceed a storage block; use fewer levels");
    ensureSize(*buffer, {passes::kLghBuild, "vertex sums", kOccupied}, bytes);
    buffer->clear();
  }
  // Every sum is bounded by (lights) x (largest light value), since trilinear weights sum to 1 and
  // offsets are in cells (|e| <= 1): that bound maps to 2^62.
  const double bound = std::max(double(lightCount) * largest, 1e-30);
  const float scale = float(kFixedPointHeadroom / bound);
  setGridParams(grid, level, table.capacity, SIZE_MAX, scale);
  table.keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  table.slotIndex.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  accPosition_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  accIntensity_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS5);
  accNormal_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS6);
  const gl::Program& scatter = floatAtomics ? scatterFloat_ : scatterFixed_;
  if (!floatAtomics) scatter.set("fixedPointScale", scale);
  forEachLightChunk(lights, lightCount, [&](size_t, size_t count) {
    scatter.set("lightCount", GLuint(count));
    scatter.dispatch1D(count, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  });

  const gl::Program& finalize = floatAtomics ? finalizeFloat_ : finalizeFixed_;
  if (!floatAtomics) finalize.set("fixedPointScale", scale);
  table.compactKeys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS7);
  table.gridLights.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  finalize.set("vertexCount", GLuint(table.count));
  finalize.dispatch1D(table.count, kLocalSize);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void LghBuildPass::gatherLevel(const LevelTable& children, const GridGeometry& grid, int level, LevelTable& table) {
  insertKeys(children.gridLights, children.count, true, table, level, grid, 8 * children.count, SIZE_MAX);
  compact(table);
  setGridParams(grid, level, table.capacity, SIZE_MAX, 0.0);
  children.gridLights.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  children.keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  children.slotIndex.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  table.gridLights.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  table.compactKeys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS7);
  gather_.set("vertexCount", GLuint(table.count));
  gather_.set("childVerticesPerAxis", GLuint(verticesPerAxis(grid, level - 1)));
  gather_.set("childTableMask", GLuint(children.capacity - 1));
  gather_.dispatch1D(table.count, 64);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void LghBuildPass::fitLookup(LevelTable& table, const GridGeometry& grid, int level) {
  const size_t capacity = nextPowerOfTwo(std::max<size_t>(1024, 2 * table.count));
  if (capacity >= table.capacity || !table.compactKeys) return;
  gl::Buffer keys({passes::kLghBuild, "vertex hash tables", kOccupied}, capacity * sizeof(GLuint));
  gl::Buffer slotIndex({passes::kLghBuild, "slot indices", kOccupied}, capacity * sizeof(GLuint));
  keys.clearUint(gpu::kEmptyKey);
  counters_.clear();
  setGridParams(grid, level, capacity, SIZE_MAX, 0.0);
  table.compactKeys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  keys.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  slotIndex.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  counters_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  for (const gl::Program* stage : {&fitInsert_, &fitIndex_}) {
    stage->set("keyCount", GLuint(table.count));
    stage->dispatch1D(table.count, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  table.keys = std::move(keys);
  table.slotIndex = std::move(slotIndex);
  table.capacity = capacity;
}

size_t LghBuildPass::countFinestVertices(const gl::Buffer& lights, size_t lightCount, const GridGeometry& grid,
                                         size_t stopAt) {
  LevelTable trial;
  insertKeys(lights, lightCount, false, trial, 1, grid, stopAt + 4096, stopAt);
  return trial.count;
}

int LghBuildPass::chooseLevelCount(const gl::Buffer& lights, size_t lightCount, const Bounds& bounds, double eMin) {
  const size_t n = bounds.litCount;
  // Largest L with |S1| < N/2 (as lgh::chooseLevelCount). S1 can never have more than
  // (2^(L-1)+1)^3 vertices, so the L where even a full grid passes need no trial.
  int best = 1;
  for (int L = 1; L <= kMaxLevels; ++L) {
    const double fullGrid = std::pow(std::ldexp(1.0, L - 1) + 1.0, 3.0);
    if (2.0 * fullGrid < double(n)) {
      best = L;
      continue;
    }
    const GridGeometry grid = makeGridAround(bounds.lower, bounds.upper, L, eMin);
    const size_t stopAt = (n + 1) / 2;  // |S1| >= ceil(N/2) fails the rule
    if (2 * countFinestVertices(lights, lightCount, grid, stopAt) < n)
      best = L;
    else
      break;
  }
  return best;
}

void LghBuildPass::execute(const gl::Buffer& lights, size_t lightCount, const LghBuildOptions& options,
                           GpuHierarchy& out, gl::Profiler* profiler) {
  if (options.levels < 0 || options.levels > kMaxLevels)
    throw std::runtime_error("LGH build: levels must be 0 (automatic) or 1.." + std::to_string(kMaxLevels) + ", got " +
                             std::to_string(options.levels));
  if (options.floatAtomics && !floatAtomicsAvailable_)
    throw std::runtime_error("LGH build: float atomics need GL_NV_shader_atomic_float, which this context lacks");
  maxLightsPerDispatch_ = options.maxLightsPerDispatch;
  const double eMin = options.eMin > 0 ? options.eMin : 1.0;
  auto scope = [&](const char* name) {
    return profiler ? std::optional<gl::Profiler::Scope>(std::in_place, *profiler, name) : std::nullopt;
  };

  out = GpuHierarchy{};
  if (lightCount == 0) return;
  gl::ensureSize(gridParams_, {passes::kLghBuild, "grid parameters"}, sizeof(gpu::LghGridParams));
  gl::ensureSize(counters_, {passes::kLghBuild, "counters"}, 4 * sizeof(GLuint));
  gl::ensureSize(boundsResult_, {passes::kLghBuild, "bounds"}, sizeof(gpu::LghBoundsResult));
  Bounds bounds;
  {
    auto s = scope("bounds");
    bounds = computeBounds(lights, lightCount);
  }
  out.litLightCount = bounds.litCount;
  int levels = options.levels;
  if (levels == 0) {
    auto s = scope("level count");
    levels = chooseLevelCount(lights, lightCount, bounds, eMin);
  }
  const GridGeometry grid = makeGridAround(bounds.lower, bounds.upper, levels, eMin);
  out.grid = grid;
  out.gathered = options.gatherCoarseLevels;
  out.levels.assign(size_t(levels) + 1, {});

  std::vector<LevelTable> tables(size_t(levels) + 1);
  for (int level = 1; level <= levels; ++level) {
    const std::string name = "S" + std::to_string(level);
    auto s = scope(name.c_str());
    if (level == 1 || !options.gatherCoarseLevels)
      scatterLevel(lights, lightCount, grid, level, bounds.largestValue, options.floatAtomics, tables[size_t(level)]);
    else
      gatherLevel(tables[size_t(level) - 1], grid, level, tables[size_t(level)]);
    // A gathered level only reads the level right below it: that level's lookup is final now (it stays,
    // for the shadow targets, fitted to its vertices), and the keys of the one below it go.
    if (level >= 2) {
      fitLookup(tables[size_t(level) - 1], grid, level - 1);
      tables[size_t(level) - 2].releaseCompactKeys();
    }
  }
  fitLookup(tables[size_t(levels)], grid, levels);
  gl::checkErrors("LGH build levels");

  {
    auto s = scope("merge");
    size_t total = 0;
    for (int level = 1; level <= levels; ++level) {
      out.levels[size_t(level)] = {total, tables[size_t(level)].count};
      total += tables[size_t(level)].count;
    }
    out.gridLightCount = total;
    out.gridLights = gl::Buffer({passes::kLghBuild, "grid lights", kOccupied},
                                std::max<size_t>(total, 1) * sizeof(gpu::GpuGridLight));
    for (int level = 1; level <= levels; ++level) {
      const LevelTable& t = tables[size_t(level)];
      if (t.count == 0) continue;
      glCopyNamedBufferSubData(t.gridLights.id(), out.gridLights.id(), 0,
                               GLintptr(out.levels[size_t(level)].offset * sizeof(gpu::GpuGridLight)),
                               GLsizeiptr(t.count * sizeof(gpu::GpuGridLight)));
    }
  }
  out.lookups.resize(size_t(levels) + 1);
  for (int level = 1; level <= levels; ++level) {
    LevelTable& t = tables[size_t(level)];
    out.lookups[size_t(level)] = {std::move(t.keys), std::move(t.slotIndex), t.capacity};
  }
  // The vertex sums and the rest of the scratch are the build's alone: the frame holds the hierarchy.
  for (gl::Buffer* scratch : {&gridParams_, &counters_, &boundsResult_, &accPosition_, &accIntensity_, &accNormal_})
    *scratch = {};
  prefixSum_.release();
  gl::checkErrors("LGH build");
}

std::vector<gpu::GpuLight> toGpuLights(const std::vector<Light>& lights) {
  std::vector<gpu::GpuLight> out(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const bool oriented = lights[i].normal != glm::vec3(0.0f);
    out[i] = {lights[i].position, oriented ? gpu::octEncode(lights[i].normal) : 0u, lights[i].intensity,
              oriented ? gpu::kLightOriented : 0u};
  }
  return out;
}

std::vector<Light> fromGpuLights(const std::vector<gpu::GpuLight>& lights) {
  std::vector<Light> out(lights.size());
  for (size_t i = 0; i < lights.size(); ++i)
    out[i] = {lights[i].position, lights[i].intensity,
              (lights[i].flags & gpu::kLightOriented) ? gpu::octDecode(lights[i].normalOct) : glm::vec3(0.0f)};
  return out;
}

}  // namespace lgh
