#include "bench/light_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "bench/bench_setup.h"
#include "bench/stats.h"
#include "bench/table.h"
#include "render/image_compare.h"
#include "render/passes/brute_force_pass.h"
#include "render/renderer.h"

namespace lgh::bench {
namespace {

// One point of the VPL-count sweep.
struct SweepRow {
  size_t target = 0, budget = 0, inputLights = 0;
  int levels = 0;
  std::vector<size_t> lightsPerLevel;
  double rasterizedPerPixel = 0, shadedPerPixel = 0;
  unsigned maxRasterized = 0;
  std::vector<double> lightPassMs, buildMs;
  std::vector<double> bruteForceMs;  // empty when over the limit
};

// One interleaving factor at a fixed VPL count.
struct InterleaveRow {
  int n = 1;
  std::vector<double> lightPassMs;  // split + light pass + resolve
  double rasterizedPerPixel = 0;
  double meanRatio = 1;             // image mean / the 1x1 image mean
  double errorVsNone = 0;           // relative RMSE against the 1x1 image
  double errorVsExact = -1;         // against the exact unshadowed sum (-1: not measured)
};

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
  command->add_option("--repeats", options.repeats, "timed frames per point")->check(CLI::PositiveNumber)->capture_default_str();
  command->add_option("--brute-force-limit", options.bruteForceLimit, "time the brute-force pass up to this many lights")
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
  std::optional<std::ofstream> csv, json;
  auto open = [](const std::string& path) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    return f;
  };
  if (!options.csvPath.empty()) csv = open(options.csvPath);
  if (!options.jsonPath.empty()) json = open(options.jsonPath);

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
  int exitCode = 0;

  // Renders with `s` (rebuilding lights when they changed) and returns the frame's stats.
  auto finite = [&](const FrameStats& stats) {
    if (stats.nonFinitePixels > 0) {
      std::fprintf(stderr, "lgh-bench light: %u NaN/Inf pixels\n", stats.nonFinitePixels);
      exitCode = 1;
    }
    return stats;
  };
  auto frame = [&](const RenderSettings& s) { return finite(bench.renderer().render(s)); };

  // --- Overdraw and light-pass time vs VPL count.
  std::vector<SweepRow> rows;
  for (size_t target : options.vplCounts) {
    SweepRow row;
    row.target = target;
    RenderSettings s = settings;
    s.lightPass.overdraw = true;
    const FrameStats counted = finite(bench.renderer().renderToVplTarget(s, target));
    row.budget = size_t(s.inputLights.vpls);
    row.inputLights = counted.lights.inputLights;
    row.levels = counted.lights.levels;
    row.lightsPerLevel = counted.lights.lightsPerLevel;
    row.rasterizedPerPixel = counted.lights.rasterizedPerPixel;
    row.shadedPerPixel = counted.lights.shadedPerPixel;
    row.maxRasterized = counted.lights.maxRasterized;
    s.lightPass.overdraw = false;  // the counter's atomics would be timed too
    for (int r = 0; r < options.repeats; ++r) row.lightPassMs.push_back(frame(s).passMs(passes::kLightPass));
    // The build is timed by changing the seed, which rebuilds S0 and the hierarchy.
    for (int r = 0; r < options.repeats; ++r) {
      s.inputLights.seed = settings.inputLights.seed + 1 + r;
      row.buildMs.push_back(frame(s).passMs(passes::kLghBuild));
    }
    if (row.inputLights <= options.bruteForceLimit) {
      s.lightPass.bruteForce = true;
      for (int r = 0; r < std::min(options.repeats, 2); ++r)
        row.bruteForceMs.push_back(frame(s).passMs(passes::kLightPass));
    }
    rows.push_back(row);
    std::fprintf(stderr, "  %s VPLs done\n", shortCount(target).c_str());
  }

  TextTable sweep({"input lights", "L", "grid lights drawn", "fragments/px", "max", "shaded/px", "light pass ms",
                   "brute force ms", "LGH build ms"});
  for (const SweepRow& r : rows) {
    size_t drawn = 0;
    for (size_t n : r.lightsPerLevel) drawn += n;
    sweep.addRow({formatCount(r.inputLights), std::to_string(r.levels), formatCount(drawn), formatMs(r.rasterizedPerPixel),
                  formatCount(r.maxRasterized), formatMs(r.shadedPerPixel), formatSpread(spreadOf(r.lightPassMs)),
                  r.bruteForceMs.empty() ? "-" : formatSpread(spreadOf(r.bruteForceMs)),
                  formatSpread(spreadOf(r.buildMs))});
  }
  std::printf("Light pass vs input lights (S0 = VPLs)\n");
  sweep.print(stdout);
  if (rows.size() >= 2) {
    const SweepRow &a = rows.front(), &b = rows.back();
    std::printf("  growth %s -> %s VPLs (x%.0f): fragments/px x%.2f, light pass x%.2f\n", shortCount(a.target).c_str(),
                shortCount(b.target).c_str(), double(b.inputLights) / double(std::max<size_t>(a.inputLights, 1)),
                b.rasterizedPerPixel / std::max(a.rasterizedPerPixel, 1e-30),
                spreadOf(b.lightPassMs).median / std::max(spreadOf(a.lightPassMs).median, 1e-30));
  }
  // Brute force costs the same per light and pixel at every count: beyond the limit, extrapolate
  // linearly from the largest count measured (marked as an estimate).
  const SweepRow* measured = nullptr;
  for (const SweepRow& r : rows)
    if (!r.bruteForceMs.empty()) measured = &r;
  if (measured) {
    const double perLight = spreadOf(measured->bruteForceMs).median / double(std::max<size_t>(measured->inputLights, 1));
    for (const SweepRow& r : rows) {
      const bool estimate = r.bruteForceMs.empty();
      const double bruteMs = estimate ? perLight * double(r.inputLights) : spreadOf(r.bruteForceMs).median;
      std::printf("  brute force / LGH light pass at %s VPLs: %s%s\n", shortCount(r.target).c_str(),
                  formatRatio(bruteMs / std::max(spreadOf(r.lightPassMs).median, 1e-30)).c_str(),
                  estimate ? " (brute force extrapolated linearly)" : "");
    }
  }

  // --- Interleaving at one VPL count.
  std::vector<InterleaveRow> interleaved;
  if (options.interleaveVpls > 0) {
    RenderSettings s = settings;
    s.inputLights.vpls = int(options.interleaveVpls);
    for (const SweepRow& r : rows)  // the budget that met this VPL count in the sweep, if it ran there
      if (r.target == options.interleaveVpls) s.inputLights.vpls = int(r.budget);
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
          gl::Texture2D out(settings.image.width, settings.image.height, GL_RGBA32F);
          bruteForce.execute(renderer.gbuffer(), renderer.inputLights().lights, renderer.inputLights().count,
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
        exitCode = 1;
      }
      interleaved.push_back(row);
    }
    std::printf("\nInterleaved sampling at %s VPLs (%s input lights; time = split + light pass + resolve)\n",
                shortCount(options.interleaveVpls).c_str(), formatCount(renderer.inputLights().count).c_str());
    TextTable table({"tiles", "fragments/px", "light pass ms", "time vs 1x1", "mean vs 1x1", "rel. RMSE vs 1x1",
                     "rel. RMSE vs exact"});
    for (const InterleaveRow& r : interleaved) {
      char mean[32], e1[32], e2[32];
      std::snprintf(mean, sizeof mean, "%.4f", r.meanRatio);
      std::snprintf(e1, sizeof e1, "%.4f", r.errorVsNone);
      std::snprintf(e2, sizeof e2, "%.4f", r.errorVsExact);
      table.addRow({std::to_string(r.n) + "x" + std::to_string(r.n), formatMs(r.rasterizedPerPixel),
                    formatSpread(spreadOf(r.lightPassMs)),
                    formatRatio(spreadOf(r.lightPassMs).median / std::max(spreadOf(interleaved.front().lightPassMs).median, 1e-30)),
                    mean, e1, r.errorVsExact < 0 ? "-" : e2});
    }
    table.print(stdout);
  }

  if (csv) {
    *csv << "table,input_lights,vpl_budget,levels,interleave,fragments_per_pixel,shaded_per_pixel,light_pass_ms_median,"
            "light_pass_ms_min,light_pass_ms_max,brute_force_ms_median,build_ms_median,error_vs_1x1,error_vs_exact\n";
    for (const SweepRow& r : rows) {
      const Spread t = spreadOf(r.lightPassMs);
      *csv << "vpls," << r.inputLights << "," << r.budget << "," << r.levels << ",1," << r.rasterizedPerPixel << ","
           << r.shadedPerPixel << "," << t.median << "," << t.min << "," << t.max << ","
           << (r.bruteForceMs.empty() ? std::string() : std::to_string(spreadOf(r.bruteForceMs).median)) << ","
           << spreadOf(r.buildMs).median << ",,\n";
    }
    for (const InterleaveRow& r : interleaved) {
      const Spread t = spreadOf(r.lightPassMs);
      *csv << "interleave," << renderer.inputLights().count << "," << options.interleaveVpls << ",," << r.n << ","
           << r.rasterizedPerPixel << ",," << t.median << "," << t.min << "," << t.max << ",,," << r.errorVsNone << ","
           << (r.errorVsExact < 0 ? std::string() : std::to_string(r.errorVsExact)) << "\n";
    }
  }
  if (json) {
    nlohmann::json j;
    j["scene"] = bench.scenePath().string();
    j["device"] = bench.context().description();
    j["width"] = settings.image.width;
    j["height"] = settings.image.height;
    j["alpha"] = settings.lightPass.alpha;
    j["start_level"] = settings.lightPass.startLevel;
    for (const SweepRow& r : rows)
      j["vpls"].push_back({{"input_lights", r.inputLights}, {"vpl_budget", r.budget}, {"levels", r.levels},
                           {"lights_per_level", r.lightsPerLevel}, {"fragments_per_pixel", r.rasterizedPerPixel},
                           {"max_fragments", r.maxRasterized}, {"shaded_per_pixel", r.shadedPerPixel},
                           {"light_pass_ms", r.lightPassMs}, {"build_ms", r.buildMs}, {"brute_force_ms", r.bruteForceMs}});
    for (const InterleaveRow& r : interleaved)
      j["interleave"].push_back({{"n", r.n}, {"fragments_per_pixel", r.rasterizedPerPixel}, {"light_pass_ms", r.lightPassMs},
                                 {"mean_ratio", r.meanRatio}, {"error_vs_1x1", r.errorVsNone},
                                 {"error_vs_exact", r.errorVsExact}});
    *json << j.dump(2) << "\n";
  }
  return exitCode;
}

}  // namespace lgh::bench
