#include "bench/engine/light_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "bench/common/bench_setup.h"
#include "bench/common/stats.h"
#include "bench/common/table.h"
#include "render/exact/brute_force_pass.h"
#include "render/image_compare.h"
#include "render/renderer.h"

namespace lgh::bench {
namespace {

// One way of drawing the light volumes at one point of the sweep: fragment counts and times.
struct VolumePath {
  double rasterizedPerPixel = 0, shadedPerPixel = 0;
  unsigned maxRasterized = 0;
  std::vector<double> lightPassMs;
  double efficiency() const { return rasterizedPerPixel > 0 ? shadedPerPixel / rasterizedPerPixel : 0.0; }
  double medianMs() const { return spreadOf(lightPassMs).median; }
};

// One point of the VPL-count sweep: a VPL count and an interleaving factor.
struct SweepRow {
  size_t target = 0, budget = 0, inputLights = 0;
  int tiles = 1;
  int levels = 0;
  std::vector<size_t> lightsPerLevel;
  VolumePath cubes, culled;          // the paper's cubes, and culled volumes
  std::vector<double> buildMs;       // 1x1 rows only
  std::vector<double> bruteForceMs;  // 1x1 rows only; empty when over the limit
  // GPU memory after the culled frames (gl::memory()): S0, the hierarchy, the light pass, everything.
  size_t inputLightBytes = 0, hierarchyBytes = 0, lightPassBytes = 0, heldBytes = 0;
  double speedUp() const { return cubes.medianMs() / std::max(culled.medianMs(), 1e-30); }
};

// One interleaving factor at a fixed VPL count.
struct InterleaveRow {
  int n = 1;
  std::vector<double> lightPassMs;  // split + light pass + resolve
  double rasterizedPerPixel = 0;
  double meanRatio = 1;      // image mean / the 1x1 image mean
  double errorVsNone = 0;    // relative RMSE against the 1x1 image
  double errorVsExact = -1;  // against the exact unshadowed sum (-1: not measured)
};

using RenderFrame = std::function<FrameStats(const RenderSettings&)>;

// Cube and culled volumes at `s`: fragment counts from one counted frame each, then `repeats` timed
// frames of each, alternating, so that a busy machine slows both alike.
SweepRow measureVolumes(const RenderFrame& frame, RenderSettings s, int repeats) {
  SweepRow row;
  row.tiles = s.lightPass.interleave;
  for (bool culling : {false, true}) {
    VolumePath& path = culling ? row.culled : row.cubes;
    s.lightPass.volumeCulling = culling;
    s.lightPass.overdraw = true;
    const FrameStats counted = frame(s);
    path.rasterizedPerPixel = counted.lights.rasterizedPerPixel;
    path.shadedPerPixel = counted.lights.shadedPerPixel;
    path.maxRasterized = counted.lights.maxRasterized;
    row.inputLights = counted.lights.inputLights;
    row.levels = counted.lights.levels;
    row.lightsPerLevel = counted.lights.lightsPerLevel;
  }
  row.budget = size_t(s.inputLights.vpls);
  s.lightPass.overdraw = false;       // the counter's atomics would be timed too
  for (int r = -1; r < repeats; ++r)  // r = -1: untimed, compiles the programs without the counter
    for (bool culling : {false, true}) {
      s.lightPass.volumeCulling = culling;
      const double ms = frame(s).passMs(passes::kLightPass);
      if (r >= 0) (culling ? row.culled : row.cubes).lightPassMs.push_back(ms);
    }
  row.inputLightBytes = gl::memory().ownerBytes(passes::kInputLights);
  row.hierarchyBytes = gl::memory().ownerBytes(passes::kLghBuild);
  row.lightPassBytes = gl::memory().ownerBytes(passes::kLightPass);
  row.heldBytes = gl::memory().liveBytes();
  return row;
}

// The hierarchy's build time (a new seed rebuilds S0 and the hierarchy) and the brute-force pass.
void measureBuildAndBruteForce(const RenderFrame& frame, RenderSettings s, int seed, const LightBenchOptions& options,
                               SweepRow& row) {
  for (int r = 0; r < options.repeats; ++r) {
    s.inputLights.seed = seed + 1 + r;
    row.buildMs.push_back(frame(s).passMs(passes::kLghBuild));
  }
  if (row.inputLights <= options.bruteForceLimit) {
    s.lightPass.bruteForce = true;
    for (int r = 0; r < std::min(options.repeats, 2); ++r)
      row.bruteForceMs.push_back(frame(s).passMs(passes::kLightPass));
  }
}

void printSweep(const std::vector<SweepRow>& rows, const LightBenchOptions& options) {
  TextTable sweep({"input lights", "tiles", "L", "grid lights drawn", "fragments/px cube", "culled", "shaded/px",
                   "efficiency cube", "culled", "light pass ms cube", "culled", "speed-up", "MB S0", "LGH",
                   "light pass", "all"});
  for (const SweepRow& r : rows) {
    size_t drawn = 0;
    for (size_t n : r.lightsPerLevel) drawn += n;
    char eCube[16], eCulled[16];
    std::snprintf(eCube, sizeof eCube, "%.2f", r.cubes.efficiency());
    std::snprintf(eCulled, sizeof eCulled, "%.2f", r.culled.efficiency());
    sweep.addRow({formatCount(r.inputLights), std::to_string(r.tiles) + "x" + std::to_string(r.tiles),
                  std::to_string(r.levels), formatCount(drawn), formatMs(r.cubes.rasterizedPerPixel),
                  formatMs(r.culled.rasterizedPerPixel), formatMs(r.culled.shadedPerPixel), eCube, eCulled,
                  formatSpread(spreadOf(r.cubes.lightPassMs)), formatSpread(spreadOf(r.culled.lightPassMs)),
                  formatRatio(r.speedUp()), formatMegabytes(r.inputLightBytes), formatMegabytes(r.hierarchyBytes),
                  formatMegabytes(r.lightPassBytes), formatMegabytes(r.heldBytes)});
  }
  std::printf(
      "Light pass vs input lights (S0 = VPLs): the paper's cubes and culled volumes, timed alternately; GPU memory "
      "held (MB)\n");
  sweep.print(stdout);
  // Growth from the smallest to the largest count, per tiling and path (the paper: x2.4 from 1K to 1M).
  for (int n : options.tiles) {
    const SweepRow *a = nullptr, *b = nullptr;
    for (const SweepRow& r : rows) {
      if (r.tiles != n) continue;
      if (!a) a = &r;
      b = &r;
    }
    if (!a || a == b) continue;
    const double lights = double(b->inputLights) / double(std::max<size_t>(a->inputLights, 1));
    std::printf(
        "  growth %s -> %s VPLs (x%.0f), %dx%d: fragments/px x%.2f cube, x%.2f culled; light pass x%.2f cube, "
        "x%.2f culled (paper: x2.4 from 1K to 1M)\n",
        shortCount(a->target).c_str(), shortCount(b->target).c_str(), lights, n, n,
        b->cubes.rasterizedPerPixel / std::max(a->cubes.rasterizedPerPixel, 1e-30),
        b->culled.rasterizedPerPixel / std::max(a->culled.rasterizedPerPixel, 1e-30),
        b->cubes.medianMs() / std::max(a->cubes.medianMs(), 1e-30),
        b->culled.medianMs() / std::max(a->culled.medianMs(), 1e-30));
  }
  std::printf("\nLGH build and brute force (1x1)\n");
  TextTable builds({"input lights", "LGH build ms", "brute force ms", "brute force / culled light pass"});
  // Brute force costs the same per light and pixel at every count: beyond the limit, extrapolate
  // linearly from the largest count measured (marked as an estimate).
  const SweepRow* measured = nullptr;
  for (const SweepRow& r : rows)
    if (!r.bruteForceMs.empty()) measured = &r;
  for (const SweepRow& r : rows) {
    if (r.tiles != 1) continue;
    std::string brute = "-", ratio = "-";
    if (measured) {
      const bool estimate = r.bruteForceMs.empty();
      const double perLight =
          spreadOf(measured->bruteForceMs).median / double(std::max<size_t>(measured->inputLights, 1));
      const double bruteMs = estimate ? perLight * double(r.inputLights) : spreadOf(r.bruteForceMs).median;
      brute = estimate ? "~" + formatMs(bruteMs) + " (extrapolated)" : formatSpread(spreadOf(r.bruteForceMs));
      ratio = formatRatio(bruteMs / std::max(r.culled.medianMs(), 1e-30));
    }
    builds.addRow({formatCount(r.inputLights), formatSpread(spreadOf(r.buildMs)), brute, ratio});
  }
  builds.print(stdout);
}

// Interleaving 1x1 / 2x2 / 4x4 at one VPL count: time, fragments, and the image's mean and error
// against 1x1 (and the exact sum). Sets `failed` when interleaving changes the mean by more than 1%.
std::vector<InterleaveRow> measureInterleaving(RenderBench& bench, const RenderFrame& frame,
                                               const std::vector<SweepRow>& rows, const LightBenchOptions& options,
                                               bool& failed) {
  Renderer& renderer = bench.renderer().renderer();
  const RenderSettings& settings = options.render.settings;
  RenderSettings s = settings;
  s.inputLights.vpls = int(options.interleaveVpls);
  for (const SweepRow& r : rows)  // the budget that met this VPL count in the sweep, if it ran there
    if (r.target == options.interleaveVpls) s.inputLights.vpls = int(r.budget);
  std::vector<InterleaveRow> interleaved;
  std::optional<ImageRGBA> none, exact;
  for (int n : {1, 2, 4}) {
    InterleaveRow row;
    row.n = n;
    s.lightPass.interleave = n;
    s.lightPass.overdraw = true;
    row.rasterizedPerPixel = frame(s).lights.rasterizedPerPixel;
    s.lightPass.overdraw = false;
    for (int r = 0; r < options.repeats; ++r) row.lightPassMs.push_back(lightPassMs(frame(s)));
    const ImageRGBA image = renderer.readImage(Aov::Irradiance);
    if (n == 1) {
      none = image;
      if (options.exactError) {
        BruteForcePass bruteForce;
        gl::Texture2D out({"bench", "brute force"}, settings.image.width, settings.image.height, GL_RGBA32F);
        bruteForce.execute({renderer.gbuffer(), renderer.inputLights().lights, renderer.inputLights().count},
                           renderer.clampDistance(), out);
        exact = fromGLRows(settings.image.width, settings.image.height, out.readRGBA());
      }
    }
    row.meanRatio = meanLuminance(image) / std::max(meanLuminance(*none), 1e-300);
    row.errorVsNone = relativeRmse(image, *none);
    if (exact) row.errorVsExact = relativeRmse(image, *exact);
    if (std::abs(row.meanRatio - 1.0) > 0.01) {
      std::fprintf(stderr, "lgh-bench light: %dx%d interleaving changes the mean by %.2f%%\n", n, n,
                   100.0 * (row.meanRatio - 1.0));
      failed = true;
    }
    interleaved.push_back(row);
  }
  return interleaved;
}

void printInterleaving(const std::vector<InterleaveRow>& interleaved, size_t vpls, size_t inputLights) {
  std::printf("\nInterleaved sampling at %s VPLs (%s input lights; time = split + light pass + resolve)\n",
              shortCount(vpls).c_str(), formatCount(inputLights).c_str());
  TextTable table({"tiles", "fragments/px", "light pass ms", "time vs 1x1", "mean vs 1x1", "rel. RMSE vs 1x1",
                   "rel. RMSE vs exact"});
  const double base = std::max(spreadOf(interleaved.front().lightPassMs).median, 1e-30);
  for (const InterleaveRow& r : interleaved) {
    char mean[32], e1[32], e2[32];
    std::snprintf(mean, sizeof mean, "%.4f", r.meanRatio);
    std::snprintf(e1, sizeof e1, "%.4f", r.errorVsNone);
    std::snprintf(e2, sizeof e2, "%.4f", r.errorVsExact);
    table.addRow({std::to_string(r.n) + "x" + std::to_string(r.n), formatMs(r.rasterizedPerPixel),
                  formatSpread(spreadOf(r.lightPassMs)), formatRatio(spreadOf(r.lightPassMs).median / base), mean, e1,
                  r.errorVsExact < 0 ? "-" : e2});
  }
  table.print(stdout);
}

void writeCsv(std::ostream& csv, const std::vector<SweepRow>& rows, const std::vector<InterleaveRow>& interleaved,
              size_t interleaveInputLights, const LightBenchOptions& options) {
  csv << "table,input_lights,vpl_budget,levels,interleave,volumes,fragments_per_pixel,shaded_per_pixel,efficiency,"
         "light_pass_ms_median,light_pass_ms_min,light_pass_ms_max,brute_force_ms_median,build_ms_median,"
         "error_vs_1x1,error_vs_exact,input_light_bytes,hierarchy_bytes,light_pass_bytes,gpu_bytes\n";
  for (const SweepRow& r : rows)
    for (bool culling : {false, true}) {
      const VolumePath& p = culling ? r.culled : r.cubes;
      const Spread t = spreadOf(p.lightPassMs);
      csv << "vpls," << r.inputLights << "," << r.budget << "," << r.levels << "," << r.tiles << ","
          << (culling ? "culled" : "cube") << "," << p.rasterizedPerPixel << "," << p.shadedPerPixel << ","
          << p.efficiency() << "," << t.median << "," << t.min << "," << t.max << ","
          << (r.bruteForceMs.empty() ? std::string() : std::to_string(spreadOf(r.bruteForceMs).median)) << ","
          << (r.buildMs.empty() ? std::string() : std::to_string(spreadOf(r.buildMs).median)) << ",,,"
          << r.inputLightBytes << "," << r.hierarchyBytes << "," << r.lightPassBytes << "," << r.heldBytes << "\n";
    }
  const bool culled = options.render.settings.lightPass.volumeCulling;
  for (const InterleaveRow& r : interleaved) {
    const Spread t = spreadOf(r.lightPassMs);
    csv << "interleave," << interleaveInputLights << "," << options.interleaveVpls << ",," << r.n << ","
        << (culled ? "culled" : "cube") << "," << r.rasterizedPerPixel << ",,," << t.median << "," << t.min << ","
        << t.max << ",,," << r.errorVsNone << ","
        << (r.errorVsExact < 0 ? std::string() : std::to_string(r.errorVsExact)) << ",,,,\n";
  }
}

void writeJson(std::ostream& out, RenderBench& bench, const std::vector<SweepRow>& rows,
               const std::vector<InterleaveRow>& interleaved, const LightBenchOptions& options) {
  const RenderSettings& settings = options.render.settings;
  nlohmann::json j;
  j["scene"] = sourceRelative(bench.scenePath());
  j["device"] = bench.context().description();
  j["width"] = settings.image.width;
  j["height"] = settings.image.height;
  j["alpha"] = settings.lightPass.alpha;
  j["start_level"] = settings.lightPass.startLevel;
  auto volumes = [](const VolumePath& p) {
    return nlohmann::json{{"fragments_per_pixel", p.rasterizedPerPixel},
                          {"max_fragments", p.maxRasterized},
                          {"shaded_per_pixel", p.shadedPerPixel},
                          {"efficiency", p.efficiency()},
                          {"light_pass_ms", p.lightPassMs}};
  };
  for (const SweepRow& r : rows)
    j["vpls"].push_back({{"input_lights", r.inputLights},
                         {"vpl_budget", r.budget},
                         {"levels", r.levels},
                         {"interleave", r.tiles},
                         {"lights_per_level", r.lightsPerLevel},
                         {"cube", volumes(r.cubes)},
                         {"culled", volumes(r.culled)},
                         {"speed_up", r.speedUp()},
                         {"build_ms", r.buildMs},
                         {"brute_force_ms", r.bruteForceMs},
                         {"gpu_bytes",
                          {{"input_lights", r.inputLightBytes},
                           {"hierarchy", r.hierarchyBytes},
                           {"light_pass", r.lightPassBytes},
                           {"all", r.heldBytes}}}});
  for (const InterleaveRow& r : interleaved)
    j["interleave"].push_back({{"n", r.n},
                               {"fragments_per_pixel", r.rasterizedPerPixel},
                               {"light_pass_ms", r.lightPassMs},
                               {"mean_ratio", r.meanRatio},
                               {"error_vs_1x1", r.errorVsNone},
                               {"error_vs_exact", r.errorVsExact}});
  out << j.dump(2) << "\n";
}

std::ofstream openForWriting(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open for writing");
  return f;
}

}  // namespace

CLI::App* addLightCommand(CLI::App& app, LightBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "light", "time the light pass and count its overdraw vs VPL count (paper Fig. 5), and interleaving 1/2/4");
  const std::map<std::string, size_t> thousands{{"K", 1000}, {"M", 1000000}};
  options.render.settings.image.width = 320;  // the bench's defaults (LightBenchOptions)
  options.render.settings.image.height = 180;
  options.render.settings.inputLights.bounces = 1;
  addRenderBenchOptions(*command, options.render, kLightOwnSettings);
  command->add_option("--vpls", options.vplCounts, "VPL counts, comma-separated (1K, 1M allowed)")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--tiles", options.tiles, "interleaving factors of the VPL-count sweep, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, int(gpu::kMaxInterleave)))
      ->capture_default_str();
  command->add_option("--repeats", options.repeats, "timed frames per point")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--brute-force-limit", options.bruteForceLimit, "time the brute-force pass up to this many lights")
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--interleave-vpls", options.interleaveVpls, "VPL count of the interleaving table (0: skip it)")
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--exact-error", options.exactError, "interleaving table: also the error against the exact sum")
      ->capture_default_str();
  command->add_option("--csv", options.csvPath, "also write the rows as CSV");
  command->add_option("--json", options.jsonPath, "also write the rows as JSON");
  return command;
}

int runLightBench(const LightBenchOptions& options) {
  // Outputs are opened first: a bad path fails before minutes of measuring.
  std::optional<std::ofstream> csv, json;
  if (!options.csvPath.empty()) csv = openForWriting(options.csvPath);
  if (!options.jsonPath.empty()) json = openForWriting(options.jsonPath);

  RenderBench bench(options.render);
  Renderer& renderer = bench.renderer().renderer();
  const RenderSettings& settings = options.render.settings;
  const int bounces = settings.inputLights.bounces;
  std::printf("lgh-bench light: %s (%s), %d x %d, %s\n", bench.scenePath().filename().string().c_str(),
              bench.sceneReason().c_str(), settings.image.width, settings.image.height,
              bench.context().description().c_str());
  std::printf(
      "clamp distance %.3g, alpha %.3g, start level %d, %d bounce%s, %d timed frames per point (median, min-max), "
      "glFinish-bracketed ms\n\n",
      double(renderer.clampDistance()), double(settings.lightPass.alpha), settings.lightPass.startLevel, bounces,
      bounces == 1 ? "" : "s", options.repeats);
  bool failed = false;
  // Renders with `s` (rebuilding lights when they changed); a NaN/Inf pixel fails the run.
  const RenderFrame frame = [&](const RenderSettings& s) {
    const FrameStats stats = bench.renderer().render(s);
    if (stats.nonFinitePixels > 0) {
      std::fprintf(stderr, "lgh-bench light: %u NaN/Inf pixels\n", stats.nonFinitePixels);
      failed = true;
    }
    return stats;
  };

  // --- Overdraw and light-pass time vs VPL count, cube and culled volumes.
  std::vector<SweepRow> rows;
  for (size_t target : options.vplCounts) {
    RenderSettings s = settings;
    bench.renderer().renderToVplTarget(s, target);  // leaves the budget that meets the target in s
    for (int n : options.tiles) {
      s.lightPass.interleave = n;
      rows.push_back(measureVolumes(frame, s, options.repeats));
      rows.back().target = target;
      if (n == 1) measureBuildAndBruteForce(frame, s, settings.inputLights.seed, options, rows.back());
      std::fprintf(stderr, "  %s VPLs %dx%d done\n", shortCount(target).c_str(), n, n);
    }
  }
  printSweep(rows, options);

  // --- Interleaving at one VPL count.
  std::vector<InterleaveRow> interleaved;
  if (options.interleaveVpls > 0) {
    interleaved = measureInterleaving(bench, frame, rows, options, failed);
    printInterleaving(interleaved, options.interleaveVpls, renderer.inputLights().count);
  }
  if (csv) writeCsv(*csv, rows, interleaved, renderer.inputLights().count, options);
  if (json) writeJson(*json, bench, rows, interleaved, options);
  return failed ? 1 : 0;
}

}  // namespace lgh::bench
