#include "bench/engine/build_bench.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "bench/common/bench_setup.h"
#include "bench/common/light_source.h"
#include "bench/common/stats.h"
#include "bench/common/table.h"
#include "lgh/grid.h"
#include "lgh/hierarchy.h"
#include "render/gl/buffer.h"
#include "render/gl/context.h"
#include "render/gl/profiler.h"
#include "render/passes/lgh_build_pass.h"

namespace lgh::bench {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
double secondsSince(Clock::time_point t) { return msSince(t) * 1e-3; }
std::string runsLabel(size_t runs) { return std::to_string(runs) + (runs == 1 ? " run" : " runs"); }

// Every level carries S0's energy exactly in exact arithmetic (trilinear weights sum to 1); the GPU
// sums in 64-bit fixed point, so anything beyond rounding of the final floats is a bug.
constexpr double kEnergyTolerance = 1e-4;

// The two GPU builds of the paper's Table 1, in its column order.
struct BuildMethod {
  const char* key;    // CSV/JSON
  const char* label;  // tables
  bool gatherCoarseLevels;
};
constexpr BuildMethod kScatter{"scatter", "scatter every level", false};
constexpr BuildMethod kGather{"gather", "S1 + gather", true};

// Timings of one GPU build method on one light set, and what its last build produced.
struct GpuBuildResult {
  std::vector<std::string> steps;                     // profiler scopes, in execution order
  std::map<std::string, std::vector<double>> stepMs;  // one sample per timed run
  std::vector<double> totalMs;                        // execute(), glFinish on both sides
  std::vector<size_t> gridLightsPerLevel;             // [l] for l in 1..L; [0] unused
  size_t gridLights = 0;
  int levels() const { return std::max(0, int(gridLightsPerLevel.size()) - 1); }
  double worstEnergyError = 0;  // max over levels and RGB of |sum I_level - sum I_S0| / sum I_S0
  int worstEnergyLevel = 0;
  // GPU memory (gl::memory()): what the built hierarchy holds, and the most the build held above what
  // was there before it (the hierarchy and its scratch together).
  size_t hierarchyBytes = 0, buildPeakBytes = 0;
};

struct CpuBuildResult {
  std::vector<double> totalMs;  // empty when skipped or not asked for
  std::string skipped;          // why, when skipped
  int levels = 0;
  size_t gridLights = 0;
};

struct LightSetResult {
  size_t lights = 0;
  GpuBuildResult scatter, gather;
  CpuBuildResult cpu;
  std::vector<std::string> failures;  // sanity checks that did not hold
};

struct ChunkTestResult {
  size_t lights = 0, lightBytes = 0, maxBlockBytes = 0;
  GpuBuildResult gather;
  std::vector<std::string> failures;
};

bool withinBudget(Clock::time_point start, int runsDone, const BuildBenchOptions& options) {
  return runsDone < options.repeats && (runsDone == 0 || secondsSince(start) < options.budgetSeconds);
}

glm::dvec3 summedIntensity(const std::vector<gpu::GpuLight>& lights) {
  glm::dvec3 sum(0.0);
  for (const gpu::GpuLight& light : lights) sum += glm::dvec3(light.intensity);
  return sum;
}

void checkEnergy(const GpuHierarchy& hierarchy, const glm::dvec3& s0Intensity, GpuBuildResult& result) {
  for (int level = 1; level <= result.levels(); ++level) {
    glm::dvec3 sum(0.0);
    for (const gpu::GpuGridLight& light : hierarchy.downloadLevel(level)) sum += glm::dvec3(light.intensity);
    for (int k = 0; k < 3; ++k) {
      const double error = std::abs(sum[k] - s0Intensity[k]) / std::max(s0Intensity[k], 1e-30);
      if (error > result.worstEnergyError) result.worstEnergyError = error, result.worstEnergyLevel = level;
    }
  }
}

// One warm-up build (the pass sizes its buffers for this light count), then up to options.repeats
// timed builds while the budget lasts.
GpuBuildResult measureGpuBuild(LghBuildPass& pass, const gl::Buffer& lights, size_t lightCount,
                               LghBuildOptions buildOptions, const BuildMethod& method, const glm::dvec3& s0Intensity,
                               const BuildBenchOptions& options) {
  buildOptions.gatherCoarseLevels = method.gatherCoarseLevels;
  gl::Profiler profiler(/*synchronous=*/true);
  GpuHierarchy hierarchy;
  GpuBuildResult result;
  auto build = [&] {
    profiler.reset();
    glFinish();
    const auto t = Clock::now();
    pass.execute(lights, lightCount, buildOptions, hierarchy, &profiler);
    glFinish();
    return msSince(t);
  };

  const auto start = Clock::now();
  hierarchy = {};
  const size_t before = gl::memory().liveBytes();
  gl::memory().resetPeak();
  build();
  result.buildPeakBytes = gl::memory().peakBytes() - before;
  result.hierarchyBytes = gl::memory().ownerBytes(passes::kLghBuild);
  for (int run = 0; withinBudget(start, run, options); ++run) {
    result.totalMs.push_back(build());
    for (const gl::PassTiming& timing : profiler.collect()) {
      if (!result.stepMs.count(timing.name)) result.steps.push_back(timing.name);
      result.stepMs[timing.name].push_back(timing.wallMs);
    }
  }

  result.gridLightsPerLevel.assign(hierarchy.levels.size(), 0);
  for (size_t level = 1; level < hierarchy.levels.size(); ++level)
    result.gridLightsPerLevel[level] = hierarchy.levels[level].count;
  result.gridLights = hierarchy.gridLightCount;
  checkEnergy(hierarchy, s0Intensity, result);
  return result;
}

// Predicts the CPU build's time from the largest set measured so far (it is linear in the lights,
// times the level count, which grows only logarithmically).
class CpuCostModel {
 public:
  std::optional<double> predictSeconds(size_t lights) const {
    if (msPerLight_ <= 0) return std::nullopt;
    return msPerLight_ * double(lights) * 1e-3;
  }
  void record(size_t lights, double ms) { msPerLight_ = ms / double(std::max<size_t>(lights, 1)); }

 private:
  double msPerLight_ = 0;
};

CpuBuildResult measureCpuBuild(const std::vector<gpu::GpuLight>& gpuLights, double eMin,
                               const BuildBenchOptions& options, CpuCostModel& costModel) {
  CpuBuildResult result;
  if (const auto predicted = costModel.predictSeconds(gpuLights.size());
      predicted && *predicted > options.cpuLimitSeconds) {
    char why[64];
    std::snprintf(why, sizeof why, "skipped (~%.3g s predicted)", *predicted);
    result.skipped = why;
    return result;
  }
  // The lights as the GPU sees them (decoded octahedral normals), so both builds get the same input.
  const std::vector<Light> lights = fromGpuLights(gpuLights);
  const auto start = Clock::now();
  for (int run = 0; withinBudget(start, run, options); ++run) {
    const auto t = Clock::now();
    // Timed like the GPU build: the level count, the bounds (makeGrid) and the levels.
    result.levels = options.levels > 0 ? options.levels : chooseLevelCount(lights, eMin);
    const Hierarchy hierarchy = buildGather(lights, makeGrid(lights, result.levels, eMin));
    result.totalMs.push_back(msSince(t));
    result.gridLights = hierarchy.lightCount();
  }
  costModel.record(lights.size(), spreadOf(result.totalMs).median);
  return result;
}

void compareMethods(const LightSetResult& set, std::vector<std::string>& failures) {
  const std::string where = shortCount(set.lights) + " lights: ";
  if (set.scatter.levels() != set.gather.levels())
    failures.push_back(where + "the builds chose different level counts (scatter " +
                       std::to_string(set.scatter.levels()) + ", gather " + std::to_string(set.gather.levels()) + ")");
  else if (set.scatter.levels() >= 1 && set.scatter.gridLightsPerLevel[1] != set.gather.gridLightsPerLevel[1])
    failures.push_back(where + "S1 differs between the builds (scatter " +
                       formatCount(set.scatter.gridLightsPerLevel[1]) + " grid lights, gather " +
                       formatCount(set.gather.gridLightsPerLevel[1]) + ")");
}

void checkEnergyResult(const GpuBuildResult& result, const std::string& what, std::vector<std::string>& failures) {
  if (result.worstEnergyError > kEnergyTolerance) {
    char message[256];
    std::snprintf(message, sizeof message, "%s: level %d carries %.3g (relative) more or less intensity than S0 (> %g)",
                  what.c_str(), result.worstEnergyLevel, result.worstEnergyError, kEnergyTolerance);
    failures.push_back(message);
  }
}

LightSetResult measureLightSet(size_t count, bool withCpu, const LightSource& source, LghBuildPass& pass,
                               const BuildBenchOptions& options, CpuCostModel& cpuCost) {
  std::printf("  %s lights:", shortCount(count).c_str());
  std::fflush(stdout);
  LightSetResult set;
  set.lights = count;
  const std::vector<gpu::GpuLight> gpuLights = toGpuLights(source.lights(count, options.seed));
  const gl::Buffer buffer = gl::Buffer::fromVector({"bench", "lights"}, gpuLights);
  const glm::dvec3 s0Intensity = summedIntensity(gpuLights);
  LghBuildOptions buildOptions;
  buildOptions.levels = options.levels;
  buildOptions.eMin = source.eMin();

  for (auto [method, result] : {std::pair{&kScatter, &set.scatter}, {&kGather, &set.gather}}) {
    *result = measureGpuBuild(pass, buffer, count, buildOptions, *method, s0Intensity, options);
    std::printf(" %s %s,", method->key, runsLabel(result->totalMs.size()).c_str());
    std::fflush(stdout);
    checkEnergyResult(*result, shortCount(count) + " lights, " + method->label, set.failures);
  }
  compareMethods(set, set.failures);
  if (withCpu) {
    set.cpu = measureCpuBuild(gpuLights, buildOptions.eMin, options, cpuCost);
    if (set.cpu.skipped.empty()) std::printf(" cpu %s,", runsLabel(set.cpu.totalMs.size()).c_str());
  }
  std::printf(" %d levels\n", set.gather.levels());
  return set;
}

ChunkTestResult runChunkTest(const LightSource& source, LghBuildPass& pass, const BuildBenchOptions& options) {
  ChunkTestResult test;
  test.lights = options.chunkTestLights;
  GLint64 maxBlock = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  test.maxBlockBytes = size_t(maxBlock);
  const std::vector<gpu::GpuLight> gpuLights = toGpuLights(source.lights(test.lights, options.seed));
  test.lightBytes = gpuLights.size() * sizeof(gpu::GpuLight);
  const gl::Buffer buffer = gl::Buffer::fromVector({"bench", "lights"}, gpuLights);
  LghBuildOptions buildOptions;
  buildOptions.levels = options.levels;
  buildOptions.eMin = source.eMin();
  test.gather = measureGpuBuild(pass, buffer, test.lights, buildOptions, kGather, summedIntensity(gpuLights), options);
  checkEnergyResult(test.gather, "chunk test, " + shortCount(test.lights) + " lights", test.failures);
  return test;
}

// ---- Output ----------------------------------------------------------------------------------

// Steps of both builds in execution order (the same list unless the level counts differ).
std::vector<std::string> stepsOf(const GpuBuildResult& a, const GpuBuildResult& b) {
  if (a.steps.empty()) return b.steps;
  std::vector<std::string> steps = a.steps;
  for (const std::string& step : b.steps)
    if (std::find(steps.begin(), steps.end(), step) == steps.end()) steps.insert(steps.end() - 1, step);
  return steps;
}

// "S3" -> 3, any other step -> 0.
int levelOfStep(const std::string& step) {
  return step.size() >= 2 && step[0] == 'S' && std::isdigit(static_cast<unsigned char>(step[1]))
             ? std::stoi(step.substr(1))
             : 0;
}

std::string stepCell(const GpuBuildResult& result, const std::string& step) {
  const auto it = result.stepMs.find(step);
  return it == result.stepMs.end() ? "-" : formatSpread(spreadOf(it->second));
}

std::string gridLightsCell(const GpuBuildResult& result, int level) {
  return level >= 1 && level <= result.levels() ? formatCount(result.gridLightsPerLevel[size_t(level)]) : "";
}

double medianRatio(const std::vector<double>& numerator, const std::vector<double>& denominator) {
  const double d = spreadOf(denominator).median;
  return d > 0 ? spreadOf(numerator).median / d : NAN;
}

void printTable1(const LightSetResult& set) {
  std::printf("\nTable 1: construction steps for %s lights (wall ms, glFinish-bracketed; median (min-max))\n",
              formatCount(set.lights).c_str());
  TextTable table({"step", std::string(kScatter.label) + " (" + runsLabel(set.scatter.totalMs.size()) + ")",
                   std::string(kGather.label) + " (" + runsLabel(set.gather.totalMs.size()) + ")", "scatter/gather",
                   "grid lights (scatter)", "grid lights (gather)"});
  for (const std::string& step : stepsOf(set.scatter, set.gather)) {
    const int level = levelOfStep(step);
    const auto scatter = set.scatter.stepMs.find(step), gather = set.gather.stepMs.find(step);
    const bool both = scatter != set.scatter.stepMs.end() && gather != set.gather.stepMs.end();
    table.addRow({step, stepCell(set.scatter, step), stepCell(set.gather, step),
                  both && level >= 2 ? formatRatio(medianRatio(scatter->second, gather->second)) : "",
                  gridLightsCell(set.scatter, level), gridLightsCell(set.gather, level)});
  }
  table.addRow({"total", formatSpread(spreadOf(set.scatter.totalMs)), formatSpread(spreadOf(set.gather.totalMs)),
                formatRatio(medianRatio(set.scatter.totalMs, set.gather.totalMs)), formatCount(set.scatter.gridLights),
                formatCount(set.gather.gridLights)});
  table.print(stdout);
  std::printf(
      "  (steps are timed one by one, each between two glFinish calls; the total is one execute() call,\n"
      "   so it includes the small host work between steps)\n");
}

void printTable2(const std::vector<LightSetResult>& sets) {
  std::printf(
      "\nTable 2: total construction time vs light count (wall ms; median (min-max)); GPU memory of the S1 + gather "
      "hierarchy (MB held after the build, the build's peak above what was held before it, bytes per input light)\n");
  TextTable table({"lights", "levels", "grid lights", kScatter.label, kGather.label, "scatter/gather",
                   "CPU S1 + gather (double)", "MB held", "build peak", "B / light"});
  for (const LightSetResult& set : sets) {
    char perLight[32];
    std::snprintf(perLight, sizeof perLight, "%.1f",
                  double(set.gather.hierarchyBytes) / double(std::max<size_t>(set.lights, 1)));
    table.addRow({formatCount(set.lights), std::to_string(set.gather.levels()), formatCount(set.gather.gridLights),
                  formatSpread(spreadOf(set.scatter.totalMs)), formatSpread(spreadOf(set.gather.totalMs)),
                  formatRatio(medianRatio(set.scatter.totalMs, set.gather.totalMs)),
                  set.cpu.totalMs.empty() ? set.cpu.skipped : formatSpread(spreadOf(set.cpu.totalMs)),
                  formatMegabytes(set.gather.hierarchyBytes), formatMegabytes(set.gather.buildPeakBytes), perLight});
  }
  table.print(stdout);
  if (std::any_of(sets.begin(), sets.end(), [](const LightSetResult& s) { return !s.cpu.skipped.empty(); }))
    std::printf(
        "  (a CPU build predicted, linearly from the largest set measured, to exceed --cpu-limit is skipped)\n");
  if (sets.size() < 2) return;
  const LightSetResult &first = sets.front(), &last = sets.back();
  std::printf("  growth %s -> %s lights (x%s): %s %s, %s %s", shortCount(first.lights).c_str(),
              shortCount(last.lights).c_str(), formatCount(last.lights / std::max<size_t>(first.lights, 1)).c_str(),
              kGather.label, formatRatio(medianRatio(last.gather.totalMs, first.gather.totalMs)).c_str(),
              kScatter.label, formatRatio(medianRatio(last.scatter.totalMs, first.scatter.totalMs)).c_str());
  if (!first.cpu.totalMs.empty() && !last.cpu.totalMs.empty())
    std::printf(", CPU %s", formatRatio(medianRatio(last.cpu.totalMs, first.cpu.totalMs)).c_str());
  std::printf("\n");
}

void printChunkTest(const ChunkTestResult& test) {
  std::printf("\nChunk test: %s lights = %s MiB of GpuLight; largest storage block %s MiB",
              formatCount(test.lights).c_str(), formatCount(test.lightBytes >> 20).c_str(),
              formatCount(test.maxBlockBytes >> 20).c_str());
  if (test.lightBytes > test.maxBlockBytes)
    std::printf(" -> the lights are bound in %zu chunks\n",
                (test.lightBytes + test.maxBlockBytes - 1) / std::max<size_t>(test.maxBlockBytes, 1));
  else
    std::printf(" -> they fit one block on this device: chunking is not exercised\n");
  std::printf("  %s: %s ms (%s), %d levels, %s grid lights, worst level energy error %.2g (level %d)\n", kGather.label,
              formatSpread(spreadOf(test.gather.totalMs)).c_str(), runsLabel(test.gather.totalMs.size()).c_str(),
              test.gather.levels(), formatCount(test.gather.gridLights).c_str(), test.gather.worstEnergyError,
              test.gather.worstEnergyLevel);
}

// One line per (light count, method, step): the CSV rows, and the "timings" array of the JSON.
struct TimingRow {
  size_t lights;
  std::string method, step;
  std::vector<double> samples;
  int levels;
  std::optional<size_t> gridLights;
  std::optional<size_t> bytes, peakBytes;  // GPU memory, "total" rows of the GPU builds
};

std::vector<TimingRow> timingRows(const std::vector<LightSetResult>& sets) {
  std::vector<TimingRow> rows;
  for (const LightSetResult& set : sets) {
    for (auto [method, result] : {std::pair{&kScatter, &set.scatter}, {&kGather, &set.gather}}) {
      for (const std::string& step : result->steps) {
        const int level = levelOfStep(step);
        rows.push_back({set.lights, method->key, step, result->stepMs.at(step), result->levels(),
                        level >= 1 ? std::optional(result->gridLightsPerLevel[size_t(level)]) : std::nullopt,
                        std::nullopt, std::nullopt});
      }
      rows.push_back({set.lights, method->key, "total", result->totalMs, result->levels(), result->gridLights,
                      result->hierarchyBytes, result->buildPeakBytes});
    }
    if (!set.cpu.totalMs.empty())
      rows.push_back({set.lights, "cpu_gather", "total", set.cpu.totalMs, set.cpu.levels, set.cpu.gridLights,
                      std::nullopt, std::nullopt});
  }
  return rows;
}

void writeCsv(std::ofstream& out, const std::vector<TimingRow>& rows) {
  out << "lights,method,step,median_ms,min_ms,max_ms,runs,levels,grid_lights,bytes,peak_bytes\n";
  auto optional = [](const std::optional<size_t>& v) { return v ? std::to_string(*v) : std::string(); };
  for (const TimingRow& row : rows) {
    const Spread s = spreadOf(row.samples);
    out << row.lights << ',' << row.method << ',' << row.step << ',' << s.median << ',' << s.min << ',' << s.max << ','
        << row.samples.size() << ',' << row.levels << ',' << optional(row.gridLights) << ',' << optional(row.bytes)
        << ',' << optional(row.peakBytes) << '\n';
  }
}

nlohmann::json toJson(const std::vector<TimingRow>& rows, const std::vector<LightSetResult>& sets,
                      const std::optional<ChunkTestResult>& chunkTest, const std::vector<std::string>& failures) {
  nlohmann::json timings = nlohmann::json::array();
  for (const TimingRow& row : rows) {
    const Spread s = spreadOf(row.samples);
    timings.push_back({{"lights", row.lights},
                       {"method", row.method},
                       {"step", row.step},
                       {"median_ms", s.median},
                       {"min_ms", s.min},
                       {"max_ms", s.max},
                       {"samples_ms", row.samples},
                       {"levels", row.levels},
                       {"grid_lights", row.gridLights ? nlohmann::json(*row.gridLights) : nlohmann::json()},
                       {"bytes", row.bytes ? nlohmann::json(*row.bytes) : nlohmann::json()},
                       {"peak_bytes", row.peakBytes ? nlohmann::json(*row.peakBytes) : nlohmann::json()}});
  }
  nlohmann::json lightSets = nlohmann::json::array();
  for (const LightSetResult& set : sets) {
    nlohmann::json entry = {{"lights", set.lights}};
    for (auto [method, result] : {std::pair{&kScatter, &set.scatter}, {&kGather, &set.gather}})
      entry[method->key] = {{"grid_lights_per_level", result->gridLightsPerLevel},
                            {"worst_energy_error", result->worstEnergyError}};
    if (!set.cpu.skipped.empty()) entry["cpu_skipped"] = set.cpu.skipped;
    lightSets.push_back(entry);
  }
  nlohmann::json json = {{"timings", timings}, {"light_sets", lightSets}, {"failures", failures}};
  if (chunkTest)
    json["chunk_test"] = {{"lights", chunkTest->lights},
                          {"light_bytes", chunkTest->lightBytes},
                          {"max_block_bytes", chunkTest->maxBlockBytes},
                          {"levels", chunkTest->gather.levels()},
                          {"grid_lights", chunkTest->gather.gridLights},
                          {"total_ms", chunkTest->gather.totalMs},
                          {"hierarchy_bytes", chunkTest->gather.hierarchyBytes},
                          {"build_peak_bytes", chunkTest->gather.buildPeakBytes},
                          {"worst_energy_error", chunkTest->gather.worstEnergyError}};
  return json;
}

std::ofstream openOutput(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  return out;
}

// The light source the options ask for, and one line saying which it is and why.
std::pair<LightSource, std::string> chooseLightSource(const BuildBenchOptions& options) {
  if (options.random) return {LightSource::inBox(), "the random box (--random)"};
  if (!options.scene.empty()) return {LightSource::onSurfaces(options.scene), "--scene " + options.scene};
  const std::filesystem::path scene = defaultBenchScene();
  if (std::filesystem::exists(scene))
    return {LightSource::onSurfaces(scene), "the default scene (" + scene.string() + ")"};
  return {LightSource::inBox(), "the random box: the default scene " + scene.string() + " is not there"};
}

}  // namespace

CLI::App* addBuildCommand(CLI::App& app, BuildBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "build", "time the GPU construction of the hierarchy: per step (paper Table 1) and vs light count (Table 2)");
  const std::map<std::string, size_t> thousands{{"K", 1000}, {"M", 1000000}};
  command->add_option("--lights", options.lightCounts, "light counts for Table 2, comma-separated (1K, 1M allowed)")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--table1-lights", options.table1Lights, "light count of Table 1 (per-step times); 0: no Table 1")
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--levels", options.levels, "levels L; 0: automatic (largest L with |S1| < N/2)")
      ->check(CLI::Range(0, LghBuildPass::kMaxLevels))
      ->capture_default_str();
  command->add_option("--repeats", options.repeats, "timed builds per method and light count (after one warm-up)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--budget", options.budgetSeconds, "seconds per method and light count: no new run starts after it")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--cpu-limit", options.cpuLimitSeconds, "skip a CPU build predicted to take longer (seconds)")
      ->capture_default_str();
  auto* scene = command->add_option("--scene", options.scene, "glTF scene whose surfaces carry the lights")
                    ->check(CLI::ExistingFile);
  command->add_flag("--random", options.random, "lights uniform in a box instead of on a scene's surfaces")
      ->excludes(scene);
  command->add_option("--csv", options.csvPath, "also write every timing as CSV");
  command->add_option("--json", options.jsonPath, "also write every timing, count and check as JSON");
  command->add_flag("--chunk-test", options.chunkTest,
                    "also build from more lights than one storage block holds (the build binds them in chunks)");
  command->add_option("--chunk-test-lights", options.chunkTestLights, "light count of the chunk test")
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->check([](const std::string& value) { return value == "0" ? std::string("must be at least 1") : std::string(); })
      ->capture_default_str();
  addBackendOption(*command, options.backend);
  command->add_option("--seed", options.seed, "seed of the light sets")->capture_default_str();
  return command;
}

int runBuildBench(const BuildBenchOptions& options) {
  // Cheap failures first: an unwritable output fails before minutes of work (a bad backend, in parsing).
  std::optional<std::ofstream> csv, json;
  if (!options.csvPath.empty()) csv = openOutput(options.csvPath);
  if (!options.jsonPath.empty()) json = openOutput(options.jsonPath);

  std::vector<size_t> counts = options.lightCounts;
  std::sort(counts.begin(), counts.end());
  counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
  counts.erase(std::remove(counts.begin(), counts.end(), size_t(0)), counts.end());

  const auto context = createContext(options.backend);
  const auto [source, sourceReason] = chooseLightSource(options);
  LghBuildPass pass(context->hasExtension("GL_NV_shader_atomic_float"));

  std::printf("lgh-bench build: GPU construction of the lighting grid hierarchy (Lin & Yuksel 2019, Tables 1-2)\n");
  std::printf("context  %s\n", context->description().c_str());
  std::printf("lights   %s\n         from %s\n", source.description().c_str(), sourceReason.c_str());
  std::printf("levels   %s, e_min %.3g\n",
              options.levels > 0 ? ("fixed at " + std::to_string(options.levels)).c_str()
                                 : "automatic (largest L with |S1| < N/2)",
              source.eMin());
  std::printf("timing   after one warm-up build, up to %d timed builds per method and light count within %g s\n",
              options.repeats, options.budgetSeconds);
  std::printf("\nmeasuring\n");

  CpuCostModel cpuCost;
  std::vector<LightSetResult> sets;
  for (size_t count : counts) sets.push_back(measureLightSet(count, true, source, pass, options, cpuCost));
  std::optional<LightSetResult> table1Set;
  if (options.table1Lights > 0) {
    const auto measured = std::find_if(sets.begin(), sets.end(),
                                       [&](const LightSetResult& s) { return s.lights == options.table1Lights; });
    table1Set = measured != sets.end() ? *measured
                                       : measureLightSet(options.table1Lights, false, source, pass, options, cpuCost);
  }
  std::optional<ChunkTestResult> chunkTest;
  if (options.chunkTest) {
    std::printf("  chunk test, %s lights\n", shortCount(options.chunkTestLights).c_str());
    std::fflush(stdout);
    chunkTest = runChunkTest(source, pass, options);
  }

  if (table1Set) printTable1(*table1Set);
  if (!sets.empty()) printTable2(sets);
  if (chunkTest) printChunkTest(*chunkTest);

  std::vector<LightSetResult> allSets = sets;
  if (table1Set &&
      std::none_of(sets.begin(), sets.end(), [&](const LightSetResult& s) { return s.lights == table1Set->lights; }))
    allSets.push_back(*table1Set);
  std::vector<std::string> failures;
  for (const LightSetResult& set : allSets) failures.insert(failures.end(), set.failures.begin(), set.failures.end());
  if (chunkTest) failures.insert(failures.end(), chunkTest->failures.begin(), chunkTest->failures.end());

  const std::vector<TimingRow> rows = timingRows(allSets);
  if (csv) writeCsv(*csv, rows);
  if (json) *json << toJson(rows, allSets, chunkTest, failures).dump(2) << "\n";

  std::printf("\nsanity checks (both builds: same level count and S1; every level carries S0's intensity within %g)\n",
              kEnergyTolerance);
  if (failures.empty()) {
    std::printf("  passed (light sets: %zu%s)\n", allSets.size(), chunkTest ? ", and the chunk test" : "");
    return 0;
  }
  for (const std::string& failure : failures) std::fprintf(stderr, "lgh-bench: check failed: %s\n", failure.c_str());
  return 1;
}

}  // namespace lgh::bench
