#include "bench/engine/frame_bench.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "bench/common/bench_setup.h"
#include "bench/common/stats.h"
#include "bench/common/table.h"
#include "render/passes/light_tree_pass.h"
#include "render/renderer.h"

namespace lgh::bench {
namespace {

// The frame's passes in order; the paper's Table 3 names in brackets where they differ.
const std::vector<std::string> kPasses{passes::kGBuffer,           passes::kDirectLight,     passes::kInputLights,
                                       passes::kLghBuild,          passes::kInterleaveSplit, passes::kLightPass,
                                       passes::kInterleaveResolve, passes::kShadowTargets,   passes::kShadowRays,
                                       passes::kShadowFilter,      passes::kComposite};

const std::string kCubeLightPass = "light pass (cubes)";  // not part of the frame: the same pass with cube volumes
// Not part of the frame either: the shadow rays aimed as in the paper (jittered cluster centres, S1 not
// selected), the pass the default's "shadow targets" + "shadow rays" replace.
const std::string kPaperShadowRays = "shadow rays (paper's targets)";
// Nor this: the shadow-ray pass with its rays untraced (ShadowSettings::trace), the rest of its work.
const std::string kUntracedShadowRays = "shadow rays, untraced";

}  // namespace

CLI::App* addFrameCommand(CLI::App& app, FrameBenchOptions& options) {
  CLI::App* command =
      app.add_subcommand("frame", "time a whole frame pass by pass for interleaving 1/2/4 (paper Table 3)");
  options.render.settings.inputLights.bounces = 1;  // the bench's default (FrameBenchOptions)
  addRenderBenchOptions(*command, options.render, kFrameOwnSettings);
  command->add_option("--interleave", options.interleave, "interleaving factors, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  command->add_option("--repeats", options.repeats, "timed frames per setting")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--compare-cubes", options.compareCubes,
                   "also time the light pass with the paper's cube volumes (row 'light pass (cubes)')")
      ->capture_default_str();
  command
      ->add_option("--compare-targets", options.compareTargets,
                   "also time the shadow rays aimed as in the paper (row 'shadow rays (paper's targets)')")
      ->capture_default_str();
  command
      ->add_option("--split-rays", options.splitRays,
                   "also time the shadow rays untraced: the pass's time split into tracing and the rest")
      ->capture_default_str();
  command
      ->add_option("--lightcut-samples", options.lightcutSamples,
                   "also time the stochastic lightcuts' frame at this many samples per pixel (0: not)")
      ->check(CLI::Range(0, int(gpu::kMaxCutNodes)))
      ->capture_default_str();
  command->add_option("--csv", options.csvPath, "also write the per-pass medians as CSV");
  return command;
}

namespace {

// Per interleaving factor: each pass's timed samples, the frame totals, and the fragments per pixel.
struct FrameTimes {
  std::map<int, std::map<std::string, std::vector<double>>> passMs;  // [n][pass] -> samples
  std::map<int, std::vector<double>> totalMs;
  std::map<int, double> fragments;
  // GPU memory: what each owner (pass names, "scene", ...) holds after the timed frames, in all, and the
  // peak while they ran.
  std::map<int, std::map<std::string, size_t>> ownerBytes;
  std::map<int, size_t> heldBytes, peakBytes;
  LightStats lights;  // of the last counted frame
  bool nonFinite = false;
};

FrameTimes measureFrames(RenderBench& bench, const RenderSettings& settings, const FrameBenchOptions& options) {
  FrameTimes t;
  for (int n : options.interleave) {
    RenderSettings s = settings;
    s.lightPass.interleave = n;
    s.lightPass.overdraw = true;
    const FrameStats counted = bench.renderer().render(s);  // warm-up, with the fragment counter
    t.fragments[n] = counted.lights.rasterizedPerPixel;
    t.lights = counted.lights;
    s.lightPass.overdraw = false;
    bench.renderer().render(s);  // without the counter: the memory measured is the timed frames'
    gl::memory().resetPeak();
    for (int r = 0; r < options.repeats; ++r) {
      s.inputLights.seed =
          settings.inputLights.seed + 1 + r;  // new VPLs every frame, as with moving lights: every pass runs
      const FrameStats stats = bench.renderer().render(s);
      t.nonFinite |= stats.nonFinitePixels > 0;
      for (const std::string& pass : kPasses) t.passMs[n][pass].push_back(stats.passMs(pass));
      t.totalMs[n].push_back(stats.totalMs());
      if (options.compareCubes) {
        // The same frame again (same lights: nothing is rebuilt) with cube volumes, for the ratio.
        RenderSettings cubes = s;
        cubes.lightPass.volumeCulling = false;
        t.passMs[n][kCubeLightPass].push_back(bench.renderer().render(cubes).passMs(passes::kLightPass));
      }
      if (options.compareTargets) {
        // The same frame again with the paper's shadow-ray targets, for the cost of aiming at input lights.
        RenderSettings paper = s;
        paper.shadows.estimator = "paper";
        t.passMs[n][kPaperShadowRays].push_back(bench.renderer().render(paper).passMs(passes::kShadowRays));
      }
      if (options.splitRays) {
        // The same frame again with the rays untraced: the pass's time without its tracing.
        RenderSettings untraced = s;
        untraced.shadows.trace = false;
        t.passMs[n][kUntracedShadowRays].push_back(bench.renderer().render(untraced).passMs(passes::kShadowRays));
      }
    }
    for (const gl::MemoryRegistry::Owner& o : gl::memory().byOwner()) t.ownerBytes[n][o.owner] = o.bytes;
    t.heldBytes[n] = gl::memory().liveBytes();
    t.peakBytes[n] = gl::memory().peakBytes();
    std::fprintf(stderr, "  %dx%d done\n", n, n);
  }
  return t;
}

// What the frame holds of the GPU's memory by owner (the passes' names, the scene), per interleaving.
void printMemory(const FrameBenchOptions& options, FrameTimes& t) {
  std::printf("\nGPU memory after the timed frames, MB by owner (gl::memory(), the engine's buffers and textures)\n\n");
  std::vector<std::string> headers{"owner"};
  for (int n : options.interleave) headers.push_back(std::to_string(n) + "x" + std::to_string(n));
  TextTable table(headers);
  std::vector<std::string> owners;  // in the order of the first interleaving's bytes, largest first
  for (int n : options.interleave)
    for (const auto& [owner, bytes] : t.ownerBytes[n])
      if (std::find(owners.begin(), owners.end(), owner) == owners.end()) owners.push_back(owner);
  const int first = options.interleave.front();
  std::stable_sort(owners.begin(), owners.end(), [&](const std::string& a, const std::string& b) {
    return t.ownerBytes[first][a] > t.ownerBytes[first][b];
  });
  for (const std::string& owner : owners) {
    std::vector<std::string> row{owner};
    for (int n : options.interleave)
      row.push_back(t.ownerBytes[n].count(owner) ? formatMegabytes(t.ownerBytes[n][owner]) : "-");
    table.addRow(row);
  }
  std::vector<std::string> held{"total"}, peak{"peak"};
  for (int n : options.interleave) {
    held.push_back(formatMegabytes(t.heldBytes[n]));
    peak.push_back(formatMegabytes(t.peakBytes[n]));
  }
  table.addRow(held);
  table.addRow(peak);
  table.print(stdout);
}

void printFrames(RenderBench& bench, const RenderSettings& settings, const FrameBenchOptions& options, FrameTimes& t) {
  const int width = settings.image.width, height = settings.image.height;
  const int bounces = settings.inputLights.bounces, k = settings.shadows.samples;
  std::printf("lgh-bench frame: %s (%s), %d x %d, %s\n", bench.scenePath().filename().string().c_str(),
              bench.sceneReason().c_str(), width, height, bench.context().description().c_str());
  std::printf(
      "%s VPLs (%d bounce%s), L = %d, %s grid lights, alpha %.3g, k = %d (at most %s shadow rays per frame); "
      "median of %d frames, glFinish-bracketed ms\n\n",
      formatCount(t.lights.vpls).c_str(), bounces, bounces == 1 ? "" : "s", t.lights.levels,
      formatCount(gridLightsOf(t.lights)).c_str(), double(settings.lightPass.alpha), k,
      formatCount(size_t(width) * size_t(height) * size_t(k)).c_str(), options.repeats);
  std::vector<std::string> headers{"pass"};
  for (int n : options.interleave) headers.push_back(std::to_string(n) + "x" + std::to_string(n));
  TextTable table(headers);
  for (const std::string& pass : kPasses) {
    std::vector<std::string> row{pass};
    for (int n : options.interleave) {
      const double median = spreadOf(t.passMs[n][pass]).median;
      row.push_back(median > 0 ? formatMs(median) : "-");
    }
    table.addRow(row);
  }
  if (options.compareCubes) {
    std::vector<std::string> cubes{kCubeLightPass}, ratio{"cubes / culled"};
    for (int n : options.interleave) {
      const double cube = spreadOf(t.passMs[n][kCubeLightPass]).median;
      const double culled = spreadOf(t.passMs[n][passes::kLightPass]).median;
      cubes.push_back(formatMs(cube));
      ratio.push_back(formatRatio(cube / std::max(culled, 1e-30)));
    }
    table.addRow(cubes);
    table.addRow(ratio);
  }
  if (options.compareTargets) {
    std::vector<std::string> paper{kPaperShadowRays}, ratio{"(targets + rays) / paper's"};
    for (int n : options.interleave) {
      const double before = spreadOf(t.passMs[n][kPaperShadowRays]).median;
      const double now =
          spreadOf(t.passMs[n][passes::kShadowTargets]).median + spreadOf(t.passMs[n][passes::kShadowRays]).median;
      paper.push_back(formatMs(before));
      ratio.push_back(formatRatio(now / std::max(before, 1e-30)));
    }
    table.addRow(paper);
    table.addRow(ratio);
  }
  if (options.splitRays) {
    // Tracing: the pass's median less its median untraced (each frame's pair differs by the rays alone).
    // (Its rays are fewer than W x H x k: slots whose light adds nothing trace none; lgh-bench rays
    // counts and traces a frame's own.)
    std::vector<std::string> rest{"shadow rays: the rest (untraced)"}, tracing{"shadow rays: tracing"};
    for (int n : options.interleave) {
      const double untraced = spreadOf(t.passMs[n][kUntracedShadowRays]).median;
      rest.push_back(formatMs(untraced));
      tracing.push_back(formatMs(std::max(spreadOf(t.passMs[n][passes::kShadowRays]).median - untraced, 0.0)));
    }
    table.addRow(rest);
    table.addRow(tracing);
  }
  std::vector<std::string> total{"total"}, frags{"fragments/px"};
  for (int n : options.interleave) {
    total.push_back(formatSpread(spreadOf(t.totalMs[n])));
    frags.push_back(formatMs(t.fragments[n]));
  }
  table.addRow(total);
  table.addRow(frags);
  table.print(stdout);
  printMemory(options, t);
}

// The stochastic lightcuts on the same lights: the tree build step by step (LightTreePass's profiler scopes
// over the renderer's S0), and whole frames with cuts shared by 8x8 blocks and per pixel (B = 1), new VPLs
// every frame as above (the tree is rebuilt in the frame).
const std::vector<std::string> kTreeSteps{"bounds", "Morton codes", "sort", "leaves", "internal levels"};
const std::vector<std::string> kLightcutPasses{passes::kLightTreeBuild, passes::kLightcutCuts,
                                               passes::kLightcutSampling, passes::kIrradianceFilter};
constexpr int kLightcutBlocks[] = {8, 1};

struct LightcutTimes {
  std::map<std::string, std::vector<double>> treeStepMs;
  std::map<int, std::map<std::string, std::vector<double>>> passMs;  // [block][pass]
  std::map<int, std::vector<double>> totalMs;
  bool nonFinite = false;
};

LightcutTimes measureLightcuts(RenderBench& bench, const RenderSettings& settings, const FrameBenchOptions& options) {
  LightcutTimes t;
  RenderSettings s = settings;
  s.indirectMethod = IndirectMethod::Rtslc;
  s.rtslc.samples = options.lightcutSamples;
  bench.renderer().render(s);  // warm-up: S0 as the LGH frames' first, the shaders compiled
  {
    const InputLights& lights = bench.renderer().renderer().inputLights();
    LightTreePass pass;
    GpuLightTree tree;
    gl::Profiler profiler(true);
    pass.execute(lights.lights, lights.count, tree, &profiler);
    profiler.collect();
    for (int r = 0; r < options.repeats; ++r) {
      pass.execute(lights.lights, lights.count, tree, &profiler);
      for (const gl::PassTiming& step : profiler.collect()) t.treeStepMs[step.name].push_back(step.wallMs);
    }
  }
  int seed = settings.inputLights.seed;
  for (int block : kLightcutBlocks) {
    s.rtslc.blockSize = block;
    bench.renderer().render(s);
    for (int r = 0; r < options.repeats; ++r) {
      s.inputLights.seed = ++seed;  // new lights every frame, also from one block size to the next
      const FrameStats stats = bench.renderer().render(s);
      t.nonFinite |= stats.nonFinitePixels > 0;
      for (const std::string& pass : kLightcutPasses) t.passMs[block][pass].push_back(stats.passMs(pass));
      t.totalMs[block].push_back(stats.totalMs());
    }
  }
  std::fprintf(stderr, "  lightcuts done\n");
  return t;
}

void printLightcuts(const RenderSettings& settings, const FrameBenchOptions& options, const FrameTimes& lgh,
                    LightcutTimes& t) {
  const double pixels = double(settings.image.width) * double(settings.image.height);
  std::printf(
      "\nstochastic lightcuts on the same lights: n = %d samples per pixel (%s shadow rays per frame), tree "
      "build step by step ([LY20] Table 1) and the frame with cuts shared by 8x8 blocks and per pixel\n\n",
      options.lightcutSamples, formatCount(size_t(pixels) * size_t(options.lightcutSamples)).c_str());
  TextTable tree({"tree build step", "ms", "share"});
  double total = 0;
  for (const std::string& step : kTreeSteps) total += spreadOf(t.treeStepMs[step]).median;
  for (const std::string& step : kTreeSteps) {
    const double ms = spreadOf(t.treeStepMs[step]).median;
    char share[16];
    std::snprintf(share, sizeof share, "%.0f%%", 100.0 * ms / std::max(total, 1e-30));
    tree.addRow({step, formatMs(ms), share});
  }
  const auto lghBuild = lgh.passMs.find(1);
  const double lghBuildMs =
      lghBuild != lgh.passMs.end() ? spreadOf(lghBuild->second.at(passes::kLghBuild)).median : 0.0;
  tree.addRow({"tree build", formatMs(total), ""});
  if (lghBuildMs > 0) tree.addRow({"LGH build (above, 1x1) / tree build", formatRatio(lghBuildMs / total), ""});
  tree.print(stdout);
  std::printf("\n");
  TextTable frame({"pass", "8x8 cuts", "per-pixel cuts"});
  for (const std::string& pass : kLightcutPasses)
    frame.addRow({pass, formatMs(spreadOf(t.passMs[8][pass]).median), formatMs(spreadOf(t.passMs[1][pass]).median)});
  std::vector<std::string> share{"cuts / sampling"};
  for (int block : kLightcutBlocks)
    share.push_back(formatRatio(spreadOf(t.passMs[block][passes::kLightcutCuts]).median /
                                std::max(spreadOf(t.passMs[block][passes::kLightcutSampling]).median, 1e-30)));
  frame.addRow(share);
  frame.addRow({"total", formatSpread(spreadOf(t.totalMs[8])), formatSpread(spreadOf(t.totalMs[1]))});
  frame.print(stdout);
}

void writeCsv(const std::string& path, const FrameBenchOptions& options, FrameTimes& t) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error(path + ": cannot open for writing");
  // bytes: the GPU memory the pass (as an owner) holds after the timed frames; total: all of it, and the
  // peak while they ran. Owners that are not passes (the scene) get rows of their own, without times.
  csv << "interleave,pass,median_ms,min_ms,max_ms,bytes,peak_bytes\n";
  auto row = [&](int n, const std::string& name, const std::vector<double>& samples, size_t bytes, std::string peak) {
    const Spread s = spreadOf(samples);
    csv << n << "," << name << "," << s.median << "," << s.min << "," << s.max << "," << bytes << "," << peak << "\n";
  };
  for (int n : options.interleave) {
    std::map<std::string, size_t> owners = t.ownerBytes[n];
    for (const std::string& pass : kPasses) {
      row(n, pass, t.passMs[n][pass], owners[pass], "");
      owners.erase(pass);
    }
    if (options.compareCubes) row(n, kCubeLightPass, t.passMs[n][kCubeLightPass], 0, "");
    if (options.compareTargets) row(n, kPaperShadowRays, t.passMs[n][kPaperShadowRays], 0, "");
    if (options.splitRays) row(n, kUntracedShadowRays, t.passMs[n][kUntracedShadowRays], 0, "");
    for (const auto& [owner, bytes] : owners) csv << n << "," << owner << ",,,," << bytes << ",\n";
    row(n, "total", t.totalMs[n], t.heldBytes[n], std::to_string(t.peakBytes[n]));
  }
}

}  // namespace

int runFrameBench(const FrameBenchOptions& options) {
  RenderBench bench(options.render);
  RenderSettings settings = options.render.settings;
  bench.renderer().renderToVplTarget(settings, size_t(settings.inputLights.vpls));
  FrameTimes times = measureFrames(bench, settings, options);
  printFrames(bench, settings, options, times);
  if (!options.csvPath.empty()) writeCsv(options.csvPath, options, times);
  bool nonFinite = times.nonFinite;
  if (options.lightcutSamples > 0) {
    LightcutTimes lightcuts = measureLightcuts(bench, settings, options);
    printLightcuts(settings, options, times, lightcuts);
    nonFinite |= lightcuts.nonFinite;
  }
  return nonFinite ? 1 : 0;
}

}  // namespace lgh::bench
