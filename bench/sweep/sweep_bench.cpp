// lgh-bench sweep: the command line (options, presets) and the run (scenes, context, cases, outputs).
// The pieces: bench/sweep/sweep_grid.h (what to measure), sweep_runner.h (the cases), sweep_reference.h (the
// reference cache), sweep_stats.h (errors, medians, fits), sweep_output.h (tables, CSV, JSON).
#include "bench/sweep/sweep_bench.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "bench/common/bench_setup.h"
#include "bench/common/progress.h"
#include "bench/common/ranks.h"
#include "bench/reference/reference.h"
#include "bench/sweep/sweep_output.h"
#include "bench/sweep/sweep_reference.h"
#include "bench/sweep/sweep_runner.h"

namespace lgh::bench {
namespace {

namespace fs = std::filesystem;

const std::map<std::string, size_t> kThousands{{"K", 1000}, {"M", 1000000}};

// Applies NAME=VALUE (render/settings.h) unless the sweep sets that setting itself.
void applySweepSetting(RenderSettings& settings, const std::string& assignment) {
  const std::string name = assignment.substr(0, assignment.find('='));
  if (std::find(kSweepOwnSettings.begin(), kSweepOwnSettings.end(), name) != kSweepOwnSettings.end())
    throw std::runtime_error("--set " + assignment + ": the sweep sets '" + name + "' itself (use its own option)");
  try {
    applySetting(settings, assignment);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("--set " + assignment + ": " + e.what());
  }
}

// The scenes, loaded (a wrong camera name fails here, naming the cameras there are).
std::vector<Scene> loadScenes(const std::vector<SceneSpec>& specs) {
  std::vector<Scene> scenes;
  for (const SceneSpec& spec : specs) {
    scenes.push_back(loadScene(spec.path));
    RenderSettings s;
    s.image.camera = spec.camera;
    resolveCamera(scenes.back(), s);
  }
  return scenes;
}

void printSummary(const SweepOptions& options, const gl::Context& context, const std::vector<Case>& cases) {
  std::printf("lgh-bench sweep: %s, %s; %d repeats per point (median)\n", timestamp().c_str(),
              context.description().c_str(), options.repeats);
  std::printf(
      "time ms (shadowed) = LGH build + light pass (+ interleaving) + shadow rays + filter; (unshadowed) = build "
      "+ light pass; errors: relative RMSE of luminance against the Embree reference\n");
  for (const Case& c : cases) printCase(c);
}

// Every case of every scene, then the tables and files. Everything that can be wrong with the input is
// found before the first frame.
int runSweep(const SweepOptions& options, std::vector<PointSpec> points) {
  std::vector<SceneSpec> specs;
  for (const std::string& s : options.scenes) specs.push_back(parseSceneSpec(s));
  if (specs.empty()) throw std::runtime_error("no scene: give --scene PATH[@CAMERA] or a --preset");
  const std::vector<Scene> scenes = loadScenes(specs);
  const fs::path outDir = options.outDir, imageDir = outDir / "images";
  fs::create_directories(options.images ? imageDir : outDir);
  fs::path cacheDir;
  if (options.cacheDir != "none")
    cacheDir = options.cacheDir.empty() ? defaultReferenceCache() : fs::path(options.cacheDir);

  const Ranks& ranks = Ranks::world();
  const auto context = createContext(options.backend);
  SweepRunner runner(ranks, options, std::move(points), imageDir, cacheDir);
  const RenderSettings& s = options.settings;
  if (ranks.root()) {
    std::fprintf(stderr, "lgh-bench sweep: %zu scene%s x %zu VPL budget%s, %zu points each, %d repeats, %d x %d, %s\n",
                 specs.size(), specs.size() == 1 ? "" : "s", options.vpls.size(), options.vpls.size() == 1 ? "" : "s",
                 runner.points().size(), options.repeats, s.image.width, s.image.height,
                 context->description().c_str());
    std::fprintf(stderr, "  output: %s; reference cache: %s%s\n", outDir.string().c_str(),
                 cacheDir.empty() ? "none" : cacheDir.string().c_str(),
                 ranks.distributed() ? ("; " + std::to_string(ranks.size()) + " MPI ranks").c_str() : "");
  }
  ProgressBar progress("sweep", double(specs.size() * runner.workPerScene()), ranks.root());
  runner.setProgress(&progress);
  std::vector<Case> cases;
  for (size_t i = 0; i < specs.size(); ++i) {
    const SceneGpu gpu(scenes[i], s.bvhLayout);
    const reference::OcclusionScene occlusion(scenes[i].positions, scenes[i].indices);
    for (size_t vpls : options.vpls) cases.push_back(runner.runCase(gpu, occlusion, specs[i], vpls));
    if (!options.scalingVpls.empty() && ranks.root()) cases.push_back(runner.runScaling(gpu, specs[i]));
  }
  progress.finish();
  if (!ranks.root()) return 0;  // rank 0 has every measurement, and writes

  printSummary(options, *context, cases);
  const QuietSampler& sampler = runner.sampler();
  writeSweepCsv(outDir / "sweep.csv", cases);
  writeSweepJson(outDir / "sweep.json", cases,
                 {context->description(), s.image.width, s.image.height, options.repeats, options.preset,
                  runner.failures(), sampler.retaken(), sampler.contended()});
  std::printf(
      "\n%zu timed samples taken again because other processes used more than %.0f%% of the machine; %zu "
      "still contended after %d tries\n",
      sampler.retaken(), 100 * QuietSampler::kBusyLimit, sampler.contended(), options.retries + 1);
  std::printf("wrote %s and %s\n", (outDir / "sweep.csv").string().c_str(), (outDir / "sweep.json").string().c_str());
  if (runner.failures().empty()) return 0;
  const size_t n = runner.failures().size();
  std::fprintf(stderr, "lgh-bench sweep: %zu check%s failed:\n", n, n == 1 ? "" : "s");
  for (const std::string& f : runner.failures()) std::fprintf(stderr, "  %s\n", f.c_str());
  return 1;
}

// The range the renderer accepts for a setting (render/settings.h), so that a grid list is checked as the
// setting itself is.
CLI::Range settingRange(const char* name) {
  const SettingInfo info = settingInfo(name);
  return CLI::Range(info.min, info.max);
}

// The grid's lists and the repeats.
void addGridOptions(CLI::App& command, SweepOptions& options) {
  command
      .add_option("--vpls", options.vpls,
                  "VPL counts, comma-separated (1K, 1M allowed); the budget is raised until the VPLs made reach each")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(kThousands))
      ->check(CLI::Range(size_t(1), size_t(16000000)))
      ->capture_default_str();
  command.add_option("--alpha", options.alphas, "alphas, comma-separated")
      ->delimiter(',')
      ->check(settingRange("alpha"))
      ->capture_default_str();
  command.add_option("--start-level", options.startLevels, "start levels (0, 1), comma-separated")
      ->delimiter(',')
      ->check(settingRange("start-level"))
      ->capture_default_str();
  command.add_option("--interleave", options.interleave, "interleaving factors n (n x n tiles), comma-separated")
      ->delimiter(',')
      ->check(settingRange("interleave"))
      ->capture_default_str();
  command
      .add_option("--shadow-samples", options.shadowSamples, "k, comma-separated (0-16; 0: unshadowed, no selection)")
      ->delimiter(',')
      ->check(settingRange("shadow-samples"))
      ->capture_default_str();
  command.add_option("--filter", options.filter, "shadow filter: on, off, or on,off")
      ->delimiter(',')
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  command
      .add_option("--frames", options.frames,
                  "still frames accumulated before each measured one, comma-separated (1: a single frame; more "
                  "turn --accumulate on)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  command
      .add_option("--rtslc-samples", options.rtslcSamples,
                  "stochastic lightcuts (the peer method) beside the LGH grid: samples per pixel n, comma-separated "
                  "(1-32; none: no lightcut points); with the same --filter and --frames")
      ->delimiter(',')
      ->check(settingRange("rtslc-samples"));
  command.add_option("--rtslc-block", options.rtslcBlocks, "lightcuts: cut-sharing blocks B (1: per pixel)")
      ->delimiter(',')
      ->check(settingRange("rtslc-block"))
      ->capture_default_str();
  command.add_option("--rtslc-interleave", options.rtslcInterleave, "lightcuts: interleaving m (1, 2, 4)")
      ->delimiter(',')
      ->check(CLI::IsMember({1, 2, 4}))
      ->capture_default_str();
  command.add_option("--repeats", options.repeats, "timed frames per point")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
}

// The reference and the baselines.
void addReferenceOptions(CLI::App& command, SweepOptions& options) {
  command
      .add_option("--reference-pixels", options.referencePixels,
                  "fraction of the pixels the reference computes (0: all, unless that exceeds --reference-budget)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command
      .add_option("--reference-budget", options.referenceBudget,
                  "pixel-light pairs above which the automatic reference takes a random pixel subset")
      ->check(CLI::Range(1e3, 1e13))
      ->capture_default_str();
  command.add_option("--uniform-lights", options.uniformLights, "uniform subsampling, unshadowed: subset sizes M")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(kThousands))
      ->capture_default_str();
  command
      .add_option("--uniform-shadowed-lights", options.uniformShadowedLights,
                  "uniform subsampling with exact visibility: subset sizes M")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(kThousands))
      ->capture_default_str();
  command
      .add_option("--brute-force-limit", options.bruteForceLimit,
                  "measure the full brute force up to this many input lights, else extrapolate")
      ->transform(CLI::AsNumberWithUnit(kThousands))
      ->capture_default_str();
  command
      .add_option("--scaling-vpls", options.scalingVpls,
                  "also time and count overdraw at these VPL counts (alpha 1, S1, k 4; no error; 0: none)")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(kThousands));
}

// Where the results go, and how the machine is used.
void addRunOptions(CLI::App& command, SweepOptions& options) {
  command.add_option("--out", options.outDir,
                     "output folder (default: bench/results for --preset readme, else sweep-results)");
  command.add_option("--cache-dir", options.cacheDir,
                     "reference cache (default: reference-cache beside lgh-bench; none: off)");
  command.add_option("--images", options.images, "write .npy images for the image strip (full references only)")
      ->capture_default_str();
  command.add_option("--threads", options.threads, "reference threads per rank (0: the host's, shared by its ranks)")
      ->capture_default_str();
  command.add_option("--tile", options.tileSize, "reference tile side in pixels (tiles are kept as they complete)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  command
      .add_option("--retries", options.retries,
                  "take a timed sample again, once the machine is quiet (waiting up to 2 min), up to this many "
                  "times while other processes use more than 25% of the machine")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  command.add_option("--set", options.set, "NAME=VALUE: any other render setting for every point (e.g. bounces=1)");
}

// The published sweep (--preset readme, docs/measurements.md): both shipped scenes at 10K and 100K VPLs, its own grid
// unless one is given, the scaling series, results into bench/results.
std::vector<PointSpec> applyReadmePreset(SweepOptions& options, const std::function<bool(const char*)>& given) {
  const fs::path sharedScenes = fs::path(LGH_SHARED_SCENES_DIR).lexically_normal();
  if (!given("--scene")) {
    for (const char* s : {"sponza_sun/sponza_sun.gltf", "cornell_emissive/cornell_emissive.gltf"})
      if (!fs::exists(sharedScenes / s))
        throw std::runtime_error("--preset readme needs " + (sharedScenes / s).string() +
                                 " (../shared/scenes beside the checkout)");
    options.scenes = {(sharedScenes / "sponza_sun/sponza_sun.gltf").string() + "@atrium",
                      (sharedScenes / "cornell_emissive/cornell_emissive.gltf").string()};
  }
  if (!given("--vpls")) options.vpls = {10000, 100000};
  if (!given("--scaling-vpls")) options.scalingVpls = {1000, 10000, 100000, 1000000};
  if (!given("--out")) options.outDir = (fs::path(LGH_SOURCE_DIR) / "bench" / "results").string();
  for (const char* grid : {"--alpha", "--start-level", "--interleave", "--shadow-samples", "--filter", "--frames"})
    if (given(grid)) return {};
  return readmePoints();
}

// A tiny run for ctest (--preset smoke): the project's Cornell box, 64 x 36, 1K VPLs, two alphas at S0, one
// point of the stochastic lightcuts.
void applySmokePreset(SweepOptions& options, const std::function<bool(const char*)>& given) {
  if (!given("--scene")) options.scenes = {(fs::path(LGH_DATA_DIR) / "cornell_box.gltf").string()};
  if (!given("--width")) options.settings.image.width = 64;
  if (!given("--height")) options.settings.image.height = 36;
  if (!given("--vpls")) options.vpls = {1000};
  if (!given("--alpha")) options.alphas = {0.5f, 2.0f};
  if (!given("--start-level")) options.startLevels = {0};
  if (!given("--interleave")) options.interleave = {1};
  if (!given("--repeats")) options.repeats = 1;
  if (!given("--uniform-lights")) options.uniformLights = {16, 64};
  if (!given("--uniform-shadowed-lights")) options.uniformShadowedLights = {2, 4};
  if (!given("--images")) options.images = false;
  if (!given("--retries")) options.retries = 0;               // ctest runs tests side by side: times are not the point
  if (!given("--rtslc-samples")) options.rtslcSamples = {2};  // one point of the peer method
}

}  // namespace

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options) {
  CLI::App* command = app.add_subcommand(
      "sweep",
      "error vs time over a parameter grid against the exact (Embree) reference, with brute-force and "
      "uniform-subsampling baselines; writes CSV, JSON and images for bench/sweep/plot_sweep.py");
  options.command = command;
  command
      ->add_option("--preset", options.preset,
                   "readme: the published sweep of docs/measurements.md (sponza_sun@atrium and cornell_emissive, 10K "
                   "and 100K VPLs, 15-35 min on 2 cores); smoke: a tiny run for ctest. Options given explicitly "
                   "override the preset's")
      ->check(CLI::IsMember({"readme", "smoke"}));
  command->add_option("--scene", options.scenes, "glTF scene, PATH or PATH@CAMERA (repeatable)");
  options.settings.image.width = 320;  // the sweep's default image
  options.settings.image.height = 180;
  addRenderSettingsOptions(*command, options.settings, kSweepOwnSettings);
  addGridOptions(*command, options);
  addReferenceOptions(*command, options);
  addRunOptions(*command, options);
  addBackendOption(*command, options.backend);
  return command;
}

int runSweepBench(SweepOptions options) {
  const std::function<bool(const char*)> given = [&](const char* name) {
    return options.command && options.command->count(name) > 0;
  };
  std::vector<PointSpec> points;
  if (options.preset == "readme") points = applyReadmePreset(options, given);
  if (options.preset == "smoke") applySmokePreset(options, given);
  if (options.outDir.empty()) options.outDir = "sweep-results";
  options.scalingVpls.erase(std::remove(options.scalingVpls.begin(), options.scalingVpls.end(), size_t(0)),
                            options.scalingVpls.end());  // --scaling-vpls 0: none
  std::vector<bool> filters;
  for (const std::string& f : options.filter) filters.push_back(f == "on");
  if (points.empty())
    points =
        grid(options.alphas, options.startLevels, options.interleave, options.shadowSamples, filters, options.frames);
  if (!options.rtslcSamples.empty()) {
    for (const PointSpec& p :
         lightcutPoints(options.rtslcSamples, options.rtslcBlocks, options.rtslcInterleave, filters, options.frames))
      points.push_back(p);
  }
  for (size_t m : options.uniformLights)
    if (m == 0) throw std::runtime_error("--uniform-lights: subset sizes must be >= 1");
  for (size_t m : options.uniformShadowedLights)
    if (m == 0) throw std::runtime_error("--uniform-shadowed-lights: subset sizes must be >= 1");
  for (const std::string& a : options.set) applySweepSetting(options.settings, a);
  if (Ranks::world().ranksOnThisHost() > 1 && options.retries > 0) {
    // The ranks of a host contend for its cores by design: a sample retaken "once the machine is quiet"
    // would wait for the other ranks forever. Such a run's times are not comparable; its errors are.
    if (Ranks::world().root())
      std::fprintf(stderr,
                   "lgh-bench sweep: %d ranks share this host: timed samples are not retaken, and the "
                   "times are contended (the errors are not)\n",
                   Ranks::world().ranksOnThisHost());
    options.retries = 0;
  }
  return runSweep(options, std::move(points));
}

}  // namespace lgh::bench
