#include "bench/light_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "bench/light_source.h"
#include "bench/stats.h"
#include "bench/table.h"
#include "render/gl/context.h"
#include "render/image_compare.h"
#include "render/passes/brute_force_pass.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

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
  double speedUp() const { return cubes.medianMs() / std::max(culled.medianMs(), 1e-30); }
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

double lightPassTotal(const FrameStats& s) {
  return s.passMs("interleave split") + s.passMs("light pass") + s.passMs("interleave resolve");
}


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
  s.lightPass.overdraw = false;  // the counter's atomics would be timed too
  for (int r = -1; r < repeats; ++r)  // r = -1: untimed, compiles the programs without the counter
    for (bool culling : {false, true}) {
      s.lightPass.volumeCulling = culling;
      const double ms = frame(s).passMs("light pass");
      if (r >= 0) (culling ? row.culled : row.cubes).lightPassMs.push_back(ms);
    }
  return row;
}

// The hierarchy's build time (a new seed rebuilds S0 and the hierarchy) and the brute-force pass.
void measureBuildAndBruteForce(const RenderFrame& frame, RenderSettings s, int seed, const LightBenchOptions& options,
                               SweepRow& row) {
  for (int r = 0; r < options.repeats; ++r) {
    s.inputLights.seed = seed + 1 + r;
    row.buildMs.push_back(frame(s).passMs("LGH build"));
  }
  if (row.inputLights <= options.bruteForceLimit) {
    s.lightPass.bruteForce = true;
    for (int r = 0; r < std::min(options.repeats, 2); ++r) row.bruteForceMs.push_back(frame(s).passMs("light pass"));
  }
}

void printSweep(const std::vector<SweepRow>& rows, const LightBenchOptions& options) {
  TextTable sweep({"input lights", "tiles", "L", "grid lights drawn", "fragments/px cube", "culled", "shaded/px",
                   "efficiency cube", "culled", "light pass ms cube", "culled", "speed-up"});
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
                  formatRatio(r.speedUp())});
  }
  std::printf("Light pass vs input lights (S0 = VPLs): the paper's cubes and culled volumes, timed alternately\n");
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
    std::printf("  growth %s -> %s VPLs (x%.0f), %dx%d: fragments/px x%.2f cube, x%.2f culled; light pass x%.2f cube, "
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
      const double perLight = spreadOf(measured->bruteForceMs).median / double(std::max<size_t>(measured->inputLights, 1));
      const double bruteMs = estimate ? perLight * double(r.inputLights) : spreadOf(r.bruteForceMs).median;
      brute = estimate ? "~" + formatMs(bruteMs) + " (extrapolated)" : formatSpread(spreadOf(r.bruteForceMs));
      ratio = formatRatio(bruteMs / std::max(r.culled.medianMs(), 1e-30));
    }
    builds.addRow({formatCount(r.inputLights), formatSpread(spreadOf(r.buildMs)), brute, ratio});
  }
  builds.print(stdout);
}

}  // namespace

CLI::App* addLightCommand(CLI::App& app, LightBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "light", "time the light pass and count its overdraw vs VPL count (paper Fig. 5), and interleaving 1/2/4");
  const std::map<std::string, size_t> thousands{{"K", 1000}, {"M", 1000000}};
  command->add_option("--scene", options.scene, "glTF scene (default: ../shared/scenes/sponza_sun, else data/cornell_box)")
      ->check(CLI::ExistingFile);
  command->add_option("--camera", options.camera, "scene camera by name (default: the first)");
  command->add_option("--width", options.width, "image width")->check(CLI::Range(16, 8192))->capture_default_str();
  command->add_option("--height", options.height, "image height")->check(CLI::Range(16, 8192))->capture_default_str();
  command->add_option("--vpls", options.vplCounts, "VPL counts, comma-separated (1K, 1M allowed)")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--bounces", options.bounces, "bounces per light path")->check(CLI::Range(1, 3))->capture_default_str();
  command->add_option("--alpha", options.alpha, "LGH alpha")->check(CLI::Range(0.25, 16.0))->capture_default_str();
  command->add_option("--clamp-distance", options.clampDistance, "d_c (0: 1e-2 x the scene diagonal)")
      ->check(CLI::Range(0.0, 1e9))
      ->capture_default_str();
  command->add_option("--start-level", options.startLevel, "finest level blended (0 or 1)")
      ->check(CLI::Range(0, 1))
      ->capture_default_str();
  command->add_option("--tiles", options.tiles, "interleaving factors of the VPL-count sweep, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, 8))
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
  command->add_option("--backend", options.backend, "OpenGL context: auto, egl, egl-device, egl-surfaceless, osmesa")
      ->capture_default_str();
  return command;
}

int runLightBench(const LightBenchOptions& options) {
  gl::ContextOptions contextOptions;
  contextOptions.backend = gl::parseBackend(options.backend);
  std::optional<std::ofstream> csv, json;
  auto open = [](const std::string& path) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    return f;
  };
  if (!options.csvPath.empty()) csv = open(options.csvPath);
  if (!options.jsonPath.empty()) json = open(options.jsonPath);

  std::string why;
  const std::filesystem::path path = chooseRenderScene(options.scene, why);
  const Scene scene = loadScene(path);
  const auto context = gl::Context::create(contextOptions);
  const SceneGpu sceneGpu(scene);
  RenderSettings settings;
  settings.image.width = options.width;
  settings.image.height = options.height;
  settings.image.camera = options.camera;
  settings.inputLights.bounces = options.bounces;
  settings.lightPass.alpha = options.alpha;
  settings.lightPass.startLevel = options.startLevel;
  settings.clampDistance = options.clampDistance;
  const CameraView view = makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  Renderer renderer(sceneGpu, settings);
  std::printf("lgh-bench light: %s (%s), %d x %d, %s\n", path.filename().string().c_str(), why.c_str(), options.width,
              options.height, context->description().c_str());
  std::printf("clamp distance %.3g, alpha %.3g, start level %d, %d bounce%s, %d timed frames per point (median, min-max), glFinish-bracketed ms\n\n",
              double(renderer.clampDistance()), double(options.alpha), options.startLevel, options.bounces, options.bounces == 1 ? "" : "s", options.repeats);
  int exitCode = 0;

  // Renders with `s` (rebuilding lights when they changed) and returns the frame's stats.
  auto frame = [&](const RenderSettings& s) {
    renderer.setSettings(s);
    FrameStats stats = renderer.render(view);
    if (stats.nonFinitePixels > 0) {
      std::fprintf(stderr, "lgh-bench light: %u NaN/Inf pixels\n", stats.nonFinitePixels);
      exitCode = 1;
    }
    return stats;
  };

  // --- Overdraw and light-pass time vs VPL count, cube and culled volumes.
  std::vector<SweepRow> rows;
  for (size_t target : options.vplCounts) {
    RenderSettings s = settings;
    s.inputLights.vpls = int(target);
    // Paths that leave the scene deposit nothing: scale the budget so the VPL count meets the target.
    const size_t got = frame(s).lights.vpls;
    if (got > 0 && got < target * 98 / 100) s.inputLights.vpls = int(std::min<double>(double(target) * double(target) / double(got), 16e6));
    for (int n : options.tiles) {
      s.lightPass.interleave = n;
      rows.push_back(measureVolumes(frame, s, options.repeats));
      SweepRow& row = rows.back();
      row.target = target;
      if (n == 1) measureBuildAndBruteForce(frame, s, settings.inputLights.seed, options, row);
      std::fprintf(stderr, "  %s VPLs %dx%d done\n", shortCount(target).c_str(), n, n);
    }
  }
  printSweep(rows, options);

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
      for (int r = 0; r < options.repeats; ++r) row.lightPassMs.push_back(lightPassTotal(frame(s)));
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
    *csv << "table,input_lights,vpl_budget,levels,interleave,volumes,fragments_per_pixel,shaded_per_pixel,efficiency,"
            "light_pass_ms_median,light_pass_ms_min,light_pass_ms_max,brute_force_ms_median,build_ms_median,"
            "error_vs_1x1,error_vs_exact\n";
    for (const SweepRow& r : rows)
      for (bool culling : {false, true}) {
        const VolumePath& p = culling ? r.culled : r.cubes;
        const Spread t = spreadOf(p.lightPassMs);
        *csv << "vpls," << r.inputLights << "," << r.budget << "," << r.levels << "," << r.tiles << ","
             << (culling ? "culled" : "cube") << "," << p.rasterizedPerPixel << "," << p.shadedPerPixel << ","
             << p.efficiency() << "," << t.median << "," << t.min << "," << t.max << ","
             << (r.bruteForceMs.empty() ? std::string() : std::to_string(spreadOf(r.bruteForceMs).median)) << ","
             << (r.buildMs.empty() ? std::string() : std::to_string(spreadOf(r.buildMs).median)) << ",,\n";
      }
    for (const InterleaveRow& r : interleaved) {
      const Spread t = spreadOf(r.lightPassMs);
      *csv << "interleave," << renderer.inputLights().count << "," << options.interleaveVpls << ",," << r.n << ","
           << (settings.lightPass.volumeCulling ? "culled" : "cube") << "," << r.rasterizedPerPixel << ",,," << t.median << "," << t.min << "," << t.max << ",,," << r.errorVsNone << ","
           << (r.errorVsExact < 0 ? std::string() : std::to_string(r.errorVsExact)) << "\n";
    }
  }
  if (json) {
    nlohmann::json j;
    j["scene"] = path.string();
    j["device"] = context->description();
    j["width"] = options.width;
    j["height"] = options.height;
    j["alpha"] = options.alpha;
    j["start_level"] = options.startLevel;
    auto path = [](const VolumePath& p) {
      return nlohmann::json{{"fragments_per_pixel", p.rasterizedPerPixel}, {"max_fragments", p.maxRasterized},
                            {"shaded_per_pixel", p.shadedPerPixel}, {"efficiency", p.efficiency()},
                            {"light_pass_ms", p.lightPassMs}};
    };
    for (const SweepRow& r : rows)
      j["vpls"].push_back({{"input_lights", r.inputLights}, {"vpl_budget", r.budget}, {"levels", r.levels},
                           {"interleave", r.tiles}, {"lights_per_level", r.lightsPerLevel}, {"cube", path(r.cubes)},
                           {"culled", path(r.culled)}, {"speed_up", r.speedUp()}, {"build_ms", r.buildMs},
                           {"brute_force_ms", r.bruteForceMs}});
    for (const InterleaveRow& r : interleaved)
      j["interleave"].push_back({{"n", r.n}, {"fragments_per_pixel", r.rasterizedPerPixel}, {"light_pass_ms", r.lightPassMs},
                                 {"mean_ratio", r.meanRatio}, {"error_vs_1x1", r.errorVsNone},
                                 {"error_vs_exact", r.errorVsExact}});
    *json << j.dump(2) << "\n";
  }
  return exitCode;
}

}  // namespace lgh::bench
