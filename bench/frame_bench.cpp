#include "bench/frame_bench.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "bench/light_source.h"
#include "bench/stats.h"
#include "bench/table.h"
#include "render/gl/context.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::bench {
namespace {

// The frame's passes in order; the paper's Table 3 names in brackets where they differ.
const std::vector<std::string> kPasses{"G-buffer",    "direct light",       "input lights", "LGH build",
                                       "interleave split", "light pass", "interleave resolve", "shadow rays",
                                       "shadow filter", "composite"};

const std::string kCubeLightPass = "light pass (cubes)";  // not part of the frame: the same pass with cube volumes

}  // namespace

CLI::App* addFrameCommand(CLI::App& app, FrameBenchOptions& options) {
  CLI::App* command = app.add_subcommand("frame", "time a whole frame pass by pass for interleaving 1/2/4 (paper Table 3)");
  command->add_option("--scene", options.scene, "glTF scene (default: ../shared/scenes/sponza_sun, else data/cornell_box)")
      ->check(CLI::ExistingFile);
  command->add_option("--camera", options.camera, "scene camera by name (default: the first)");
  command->add_option("--width", options.width, "image width")->check(CLI::Range(16, 8192))->capture_default_str();
  command->add_option("--height", options.height, "image height")->check(CLI::Range(16, 8192))->capture_default_str();
  command->add_option("--vpls", options.vpls, "VPL budget")->check(CLI::Range(0, 16000000))->capture_default_str();
  command->add_option("--bounces", options.bounces, "bounces per light path")->check(CLI::Range(1, 3))->capture_default_str();
  command->add_option("--shadow-samples", options.shadowSamples, "k")->check(CLI::Range(0, 16))->capture_default_str();
  command->add_option("--alpha", options.alpha, "LGH alpha")->check(CLI::Range(0.25, 16.0))->capture_default_str();
  command->add_option("--interleave", options.interleave, "interleaving factors, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  command->add_option("--repeats", options.repeats, "timed frames per setting")->check(CLI::PositiveNumber)->capture_default_str();
  command->add_option("--compare-cubes", options.compareCubes,
                      "also time the light pass with the paper's cube volumes (row 'light pass (cubes)')")
      ->capture_default_str();
  command->add_option("--csv", options.csvPath, "also write the per-pass medians as CSV");
  command->add_option("--backend", options.backend, "OpenGL context")->capture_default_str();
  return command;
}

int runFrameBench(const FrameBenchOptions& options) {
  gl::ContextOptions contextOptions;
  contextOptions.backend = gl::parseBackend(options.backend);
  std::string why;
  const std::filesystem::path path = chooseRenderScene(options.scene, why);
  const Scene scene = loadScene(path);
  const auto context = gl::Context::create(contextOptions);
  const SceneGpu sceneGpu(scene);
  RenderSettings settings;
  settings.image.width = options.width;
  settings.image.height = options.height;
  settings.image.camera = options.camera;
  settings.inputLights.vpls = options.vpls;
  settings.inputLights.bounces = options.bounces;
  settings.shadows.samples = options.shadowSamples;
  settings.lightPass.alpha = options.alpha;
  const CameraView view = makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height);
  Renderer renderer(sceneGpu, settings);
  int exitCode = 0;
  {
    // Paths that leave the scene deposit nothing: scale the budget so the VPL count meets --vpls.
    const size_t got = renderer.render(view).lights.vpls, target = size_t(options.vpls);
    if (got > 0 && got < target * 98 / 100) settings.inputLights.vpls = int(std::min(double(target) * double(target) / double(got), 16e6));
  }

  std::map<int, std::map<std::string, std::vector<double>>> times;  // [n][pass] -> samples
  std::map<int, std::vector<double>> totals;
  std::map<int, double> fragments;
  LightStats lights;
  for (int n : options.interleave) {
    RenderSettings s = settings;
    s.lightPass.interleave = n;
    s.lightPass.overdraw = true;
    renderer.setSettings(s);
    const FrameStats counted = renderer.render(view);  // warm-up, with the fragment counter
    fragments[n] = counted.lights.rasterizedPerPixel;
    lights = counted.lights;
    s.lightPass.overdraw = false;
    for (int r = 0; r < options.repeats; ++r) {
      s.inputLights.seed = settings.inputLights.seed + 1 + r;  // new VPLs every frame, as with moving lights: every pass runs
      renderer.setSettings(s);
      const FrameStats stats = renderer.render(view);
      if (stats.nonFinitePixels > 0) exitCode = 1;
      for (const std::string& pass : kPasses) times[n][pass].push_back(stats.passMs(pass));
      totals[n].push_back(stats.totalMs());
      if (options.compareCubes) {
        // The same frame again (same lights: nothing is rebuilt) with cube volumes, for the ratio.
        RenderSettings cubes = s;
        cubes.lightPass.volumeCulling = false;
        renderer.setSettings(cubes);
        times[n][kCubeLightPass].push_back(renderer.render(view).passMs("light pass"));
      }
    }
    std::fprintf(stderr, "  %dx%d done\n", n, n);
  }

  size_t gridLights = 0;
  for (size_t l = 1; l < lights.lightsPerLevel.size(); ++l) gridLights += lights.lightsPerLevel[l];
  std::printf("lgh-bench frame: %s (%s), %d x %d, %s\n", path.filename().string().c_str(), why.c_str(), options.width,
              options.height, context->description().c_str());
  std::printf("%s VPLs (%d bounce%s), L = %d, %s grid lights, alpha %.3g, k = %d (%s shadow rays per frame); "
              "median of %d frames, glFinish-bracketed ms\n\n",
              formatCount(lights.vpls).c_str(), options.bounces, options.bounces == 1 ? "" : "s", lights.levels,
              formatCount(gridLights).c_str(), double(options.alpha), options.shadowSamples,
              formatCount(size_t(options.width) * size_t(options.height) * size_t(options.shadowSamples)).c_str(),
              options.repeats);
  std::vector<std::string> headers{"pass"};
  for (int n : options.interleave) headers.push_back(std::to_string(n) + "x" + std::to_string(n));
  TextTable table(headers);
  for (const std::string& pass : kPasses) {
    std::vector<std::string> row{pass};
    for (int n : options.interleave) {
      const double median = spreadOf(times[n][pass]).median;
      row.push_back(median > 0 ? formatMs(median) : "-");
    }
    table.addRow(row);
  }
  if (options.compareCubes) {
    std::vector<std::string> cubes{kCubeLightPass}, ratio{"cubes / culled"};
    for (int n : options.interleave) {
      const double cube = spreadOf(times[n][kCubeLightPass]).median, culled = spreadOf(times[n]["light pass"]).median;
      cubes.push_back(formatMs(cube));
      ratio.push_back(formatRatio(cube / std::max(culled, 1e-30)));
    }
    table.addRow(cubes);
    table.addRow(ratio);
  }
  std::vector<std::string> total{"total"}, frags{"fragments/px"};
  for (int n : options.interleave) {
    total.push_back(formatSpread(spreadOf(totals[n])));
    frags.push_back(formatMs(fragments[n]));
  }
  table.addRow(total);
  table.addRow(frags);
  table.print(stdout);

  if (!options.csvPath.empty()) {
    std::ofstream csv(options.csvPath);
    if (!csv) throw std::runtime_error(options.csvPath + ": cannot open for writing");
    csv << "interleave,pass,median_ms,min_ms,max_ms\n";
    for (int n : options.interleave) {
      for (const std::string& pass : kPasses) {
        const Spread t = spreadOf(times[n][pass]);
        csv << n << "," << pass << "," << t.median << "," << t.min << "," << t.max << "\n";
      }
      if (options.compareCubes) {
        const Spread c = spreadOf(times[n][kCubeLightPass]);
        csv << n << "," << kCubeLightPass << "," << c.median << "," << c.min << "," << c.max << "\n";
      }
      const Spread t = spreadOf(totals[n]);
      csv << n << ",total," << t.median << "," << t.min << "," << t.max << "\n";
    }
  }
  return exitCode;
}

}  // namespace lgh::bench
