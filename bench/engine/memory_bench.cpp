#include "bench/engine/memory_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "bench/common/table.h"
#include "render/gl/memory.h"
#include "render/passes/lgh_build_pass.h"
#include "render/renderer.h"
#include "shared/lgh_types.h"

namespace lgh::bench {

CLI::App* addMemoryCommand(CLI::App& app, MemoryBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "memory", "GPU memory by owner against input lights, image size, k, interleaving and extent, both methods");
  options.render.settings.image.width = 320;  // the bench's defaults (MemoryBenchOptions)
  options.render.settings.image.height = 180;
  options.render.settings.inputLights.bounces = 1;
  addRenderBenchOptions(*command, options.render, kMemoryOwnSettings);
  command
      ->add_option("--vpls", options.vplCounts, "VPL budgets of the lights table, comma-separated (1K, 4.5M allowed)")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(std::map<std::string, double>{{"K", 1e3}, {"M", 1e6}}))
      ->check(CLI::Range(1.0, 16e6));
  command->add_option("--fixed-vpls", options.fixedVpls, "VPL budget of the other tables")
      ->transform(CLI::AsNumberWithUnit(std::map<std::string, size_t>{{"K", 1000}, {"M", 1000000}}))
      ->capture_default_str();
  command->add_option("--sizes", options.sizes, "image sizes of the size table, WxH, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--markdown", options.markdownPath, "also write the tables here (Markdown)");
  return command;
}

namespace {

// What the registry holds now, by what each object's size follows (its label's scaledBy).
struct Held {
  size_t total = 0, peak = 0;
  size_t pixels = 0;  // objects sized by the image ("width x height" ...)
  size_t lights = 0;  // by the lights: S0, the hierarchy's vertices, grid lights, the tree
  size_t fixed = 0;   // by nothing a setting changes (uniforms, the scene's own buffers)
  std::map<std::string, size_t> owners;
  std::map<std::string, size_t> objects;  // by "owner: name" (objects of one name summed)
  std::string dominant;                   // the owner holding most

  size_t owner(const char* name) const {
    const auto it = owners.find(name);
    return it == owners.end() ? 0 : it->second;
  }
};

Held held() {
  Held h;
  h.total = gl::memory().liveBytes();
  h.peak = gl::memory().peakBytes();
  for (const gl::MemoryRegistry::Object& o : gl::memory().objects()) {
    h.owners[o.label.owner] += o.bytes;
    h.objects[o.label.text()] += o.bytes;
    if (o.label.scaledBy.find(kImageSize) != std::string::npos)
      h.pixels += o.bytes;
    else if (!o.label.scaledBy.empty())
      h.lights += o.bytes;
    else
      h.fixed += o.bytes;
  }
  for (const auto& [owner, bytes] : h.owners)
    if (h.dominant.empty() || bytes > h.owners[h.dominant]) h.dominant = owner;
  return h;
}

// One frame with `s` from a clean peak; what it holds after it. A configuration refused before the driver
// sees it (gl::OutOfMemory, or a structure's own limit) is reported, not fatal: its message is the measurement.
struct Measured {
  Held held;
  size_t inputLights = 0;
  std::string refused;
};

Measured measure(RenderBench& bench, const RenderSettings& s) {
  Measured m;
  // From what a frame without indirect light holds, so that the peak is this configuration's own build.
  RenderSettings off = s;
  off.indirectMethod = IndirectMethod::None;
  bench.renderer().render(off);
  gl::memory().resetPeak();
  try {
    const FrameStats stats = bench.renderer().render(s);
    if (s.accumulation.enabled) bench.renderer().render(s);  // the history made and swapped once
    m.inputLights = stats.lights.inputLights;
  } catch (const std::runtime_error& e) {
    m.refused = e.what();
    bench.renderer().render(off);  // the next configuration starts from nothing of this one
  }
  m.held = held();
  return m;
}

std::string mb(size_t bytes) { return formatMegabytes(bytes); }

std::string perUnit(double bytes, double units) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", units > 0 ? bytes / units : 0.0);
  return text;
}

const char* structureOwner(const RenderSettings& s) {
  return s.indirectMethod == IndirectMethod::Rtslc ? passes::kLightTreeBuild : passes::kLghBuild;
}

std::pair<int, int> parseSize(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0)
    throw std::invalid_argument("--sizes: '" + text + "' is not WxH");
  return {w, h};
}

// Markdown tables, printed and (with --markdown) written.
class Report {
 public:
  void heading(const std::string& text) { out_ << "\n" << text << "\n\n"; }
  void row(const std::vector<std::string>& cells) {
    out_ << "|";
    for (const std::string& c : cells) out_ << " " << c << " |";
    out_ << "\n";
    if (!headerDone_) {
      out_ << "|";
      for (size_t i = 0; i < cells.size(); ++i) out_ << (i == 0 ? "---|" : "---:|");
      out_ << "\n";
      headerDone_ = true;
    }
  }
  // A footnote printed below the table: returns its marker.
  std::string note(const std::string& text) {
    notes_.push_back(text);
    return "(" + std::to_string(notes_.size()) + ")";
  }
  void endTable() {
    headerDone_ = false;
    if (!notes_.empty()) out_ << "\n";
    for (size_t i = 0; i < notes_.size(); ++i) out_ << "(" << i + 1 << ") " << notes_[i] << "\n";
    notes_.clear();
  }
  void line(const std::string& text) { out_ << text << "\n"; }
  // A property the tables must show (the bench's exit code says whether they all held).
  void check(bool holds, const std::string& what) {
    if (!holds) failures_.push_back(what);
  }
  const std::vector<std::string>& failures() const { return failures_; }
  std::string text() const { return out_.str(); }

 private:
  std::ostringstream out_;
  bool headerDone_ = false;
  std::vector<std::string> notes_;
  std::vector<std::string> failures_;
};

bool near(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance * std::max(std::abs(b), 1e-30); }

void lightsTable(RenderBench& bench, const MemoryBenchOptions& options, Report& r) {
  const RenderSettings& base = options.render.settings;
  const double pixels = double(base.image.width) * double(base.image.height);
  r.heading("Against the input lights (" + std::to_string(base.image.width) + "x" + std::to_string(base.image.height) +
            ", k = " + std::to_string(base.shadows.samples) + ", 1x1; MB unless said; B/light: what follows the " +
            "lights over the input lights; B/px: what follows the image over its pixels)");
  r.row({"method", "VPL budget", "input lights", "all", "S0", "hierarchy / tree", "B / light", "B / px",
         "shadow rays B / px", "peak", "largest owner"});
  Held largestLgh;                               // the last LGH row, broken down below
  std::map<std::string, double> shadowPerPixel;  // the first row's, per method
  for (const char* method : {"lgh", "rtslc"})
    for (const double budget : options.vplCounts) {
      const size_t vpls = size_t(budget);
      RenderSettings s = base;
      s.indirectMethod = choiceValue<IndirectMethod>(method, kIndirectMethodChoices);
      s.inputLights.vpls = int(vpls);
      const Measured m = measure(bench, s);
      std::fprintf(stderr, "  %s %s VPLs done\n", method, shortCount(vpls).c_str());
      if (!m.refused.empty()) {
        r.row({method, shortCount(vpls), "-", "refused " + r.note(m.refused), "", "", "", "", "", "", ""});
        continue;
      }
      const Held& h = m.held;
      if (std::string(method) == "lgh") largestLgh = h;
      // The shadow sampling's memory per pixel is fixed: the same at every light count.
      const double shadow = double(h.owner(passes::kShadowRays)) / pixels;
      if (!shadowPerPixel.count(method)) shadowPerPixel[method] = shadow;
      r.check(shadow == shadowPerPixel[method], std::string(method) + " at " + shortCount(vpls) +
                                                    " VPLs: the shadow sampling holds " + perUnit(shadow, 1) +
                                                    " B/px, not the first row's " + perUnit(shadowPerPixel[method], 1));
      r.row({method, shortCount(vpls), formatCount(m.inputLights), mb(h.total), mb(h.owner(passes::kInputLights)),
             mb(h.owner(structureOwner(s))), perUnit(double(h.lights), double(m.inputLights)),
             perUnit(double(h.pixels), pixels),
             std::string(method) == "lgh" ? perUnit(double(h.owner(passes::kShadowRays)), pixels) : "-", mb(h.peak),
             h.dominant});
    }
  r.endTable();
  // What the lights' part is made of at the largest LGH row.
  std::vector<std::pair<std::string, size_t>> objects(largestLgh.objects.begin(), largestLgh.objects.end());
  std::sort(objects.begin(), objects.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  r.heading("The largest LGH row's objects, largest first (MB)");
  r.row({"object", "MB", "share"});
  for (size_t i = 0; i < std::min<size_t>(objects.size(), 10); ++i)
    r.row({objects[i].first, mb(objects[i].second),
           perUnit(100.0 * double(objects[i].second), double(largestLgh.total)) + "%"});
  r.endTable();
}

void sizesTable(RenderBench& bench, const MemoryBenchOptions& options, Report& r) {
  r.heading("Against the image size (" + shortCount(options.fixedVpls) +
            " VPL budget, k = " + std::to_string(options.render.settings.shadows.samples) + ", 1x1)");
  r.row({"method", "image", "all MB", "image part MB", "B / px", "lights part MB", "fixed MB", "largest owner"});
  for (const char* method : {"lgh", "rtslc"}) {
    double firstPerPixel = -1;
    for (const std::string& size : options.sizes) {
      RenderSettings s = options.render.settings;
      s.indirectMethod = choiceValue<IndirectMethod>(method, kIndirectMethodChoices);
      s.inputLights.vpls = int(options.fixedVpls);
      std::tie(s.image.width, s.image.height) = parseSize(size);
      const Measured m = measure(bench, s);
      const Held& h = m.held;
      const double perPixel = double(h.pixels) / (double(s.image.width) * s.image.height);
      r.row({method, size, mb(h.total), mb(h.pixels), perUnit(perPixel, 1), mb(h.lights), mb(h.fixed), h.dominant});
      if (firstPerPixel < 0) firstPerPixel = perPixel;
      r.check(near(perPixel, firstPerPixel, 0.01), std::string(method) + " at " + size + ": " + perUnit(perPixel, 1) +
                                                       " B/px, not the smallest image's " + perUnit(firstPerPixel, 1));
    }
  }
  r.endTable();
}

void samplesTable(RenderBench& bench, const MemoryBenchOptions& options, Report& r) {
  const RenderSettings& base = options.render.settings;
  const double pixels = double(base.image.width) * double(base.image.height);
  r.heading("Against k and interleaving (" + shortCount(options.fixedVpls) + " VPL budget, " +
            std::to_string(base.image.width) + "x" + std::to_string(base.image.height) +
            "; the lightcuts' n and m for comparison)");
  r.row({"method", "k / n", "interleave", "accumulate", "all MB", "B / px", "shadow rays B / px", "history B / px"});
  auto add = [&](const RenderSettings& s, const std::string& samples) {
    const Held h = measure(bench, s).held;
    r.row({choiceName(s.indirectMethod, kIndirectMethodChoices), samples,
           std::to_string(s.lightPass.interleave) + "x" + std::to_string(s.lightPass.interleave),
           s.accumulation.enabled ? "on" : "off", mb(h.total), perUnit(double(h.pixels), pixels),
           perUnit(double(h.owner(passes::kShadowRays)), pixels),
           perUnit(double(h.owner(passes::kAccumulation)), pixels)});
  };
  for (int k : {0, 1, 4, 16})
    for (int n : {1, 2, 4}) {
      RenderSettings s = base;
      s.inputLights.vpls = int(options.fixedVpls);
      s.shadows.samples = k;
      s.lightPass.interleave = n;
      add(s, std::to_string(k));
    }
  RenderSettings accumulating = base;
  accumulating.inputLights.vpls = int(options.fixedVpls);
  accumulating.accumulation.enabled = true;
  add(accumulating, std::to_string(accumulating.shadows.samples));
  // The lightcuts' n samples per pixel with m x m interleaving (a cut of n m^2 <= 32 nodes).
  for (auto [n, m] : {std::pair{8, 1}, {8, 2}, {2, 4}}) {
    RenderSettings s = base;
    s.inputLights.vpls = int(options.fixedVpls);
    s.indirectMethod = IndirectMethod::Rtslc;
    s.rtslc.samples = n;
    s.rtslc.interleave = m;
    const Held h = measure(bench, s).held;
    r.row({"rtslc", std::to_string(n), std::to_string(m) + "x" + std::to_string(m), "off", mb(h.total),
           perUnit(double(h.pixels), pixels), "-", "0.0"});
  }
  r.endTable();
}

// The hierarchy of the renderer's own S0, and of the same lights 1,000 times farther apart.
void extentTable(RenderBench& bench, const MemoryBenchOptions& options, Report& r) {
  RenderSettings s = options.render.settings;
  s.inputLights.vpls = int(options.fixedVpls);
  bench.renderer().render(s);
  const InputLights& s0 = bench.renderer().renderer().inputLights();
  std::vector<gpu::GpuLight> lights = s0.lights.download<gpu::GpuLight>(s0.count);
  const LghBuildOptions rendered = bench.renderer().renderer().buildOptions();
  RenderSettings off = s;
  off.indirectMethod = IndirectMethod::None;
  bench.renderer().render(off);  // only the scene held: the hierarchies below are all there is
  LghBuildPass pass(GLAD_GL_NV_shader_atomic_float != 0);
  r.heading("Against the scene's extent (the " + formatCount(lights.size()) +
            " input lights above, and the same lights with positions x1000; S1 + gather, L by the paper's rule)");
  r.row({"extent", "levels", "grid lights", "hierarchy MB", "B / input light"});
  std::vector<size_t> bytesAt;
  for (float scale : {1.0f, 1000.0f}) {
    std::vector<gpu::GpuLight> scaled = lights;
    for (gpu::GpuLight& l : scaled) l.position *= scale;
    const gl::Buffer buffer = gl::Buffer::fromVector({"bench", "scaled lights"}, scaled);
    GpuHierarchy hierarchy;
    LghBuildOptions buildOptions = rendered;
    buildOptions.eMin = rendered.eMin * double(scale);
    pass.execute(buffer, scaled.size(), buildOptions, hierarchy);
    const size_t bytes = gl::memory().ownerBytes(passes::kLghBuild);
    bytesAt.push_back(bytes);
    r.row({scale == 1.0f ? "x1" : "x1000", std::to_string(hierarchy.grid.levels), formatCount(hierarchy.gridLightCount),
           mb(bytes), perUnit(double(bytes), double(scaled.size()))});
  }
  r.endTable();
  r.check(near(double(bytesAt[1]), double(bytesAt[0]), 0.01),
          "the hierarchy x1000 in extent holds " + mb(bytesAt[1]) + " MB, not " + mb(bytesAt[0]));
}

}  // namespace

int runMemoryBench(const MemoryBenchOptions& options) {
  RenderBench bench(options.render);
  const RenderSettings& s = options.render.settings;
  Report report;
  report.line("lgh-bench memory: " + sourceRelative(bench.scenePath()) + " (" + bench.sceneReason() + "), " +
              bench.context().description() + "; largest storage block " +
              gl::formatBytes(double(gl::maxStorageBlockBytes())) + "; " + std::to_string(s.inputLights.bounces) +
              " bounce(s), alpha " + std::to_string(s.lightPass.alpha).substr(0, 4));
  const size_t sceneBytes = gl::memory().ownerBytes(passes::kScene);
  report.line("The scene's own buffers (geometry, BVH, materials, textures): " + gl::formatBytes(double(sceneBytes)) +
              ", in every row's 'all'.");
  lightsTable(bench, options, report);
  sizesTable(bench, options, report);
  samplesTable(bench, options, report);
  extentTable(bench, options, report);
  std::printf("%s", report.text().c_str());
  if (!options.markdownPath.empty()) {
    std::ofstream out(options.markdownPath);
    if (!out) throw std::runtime_error(options.markdownPath + ": cannot open for writing");
    out << report.text();
  }
  for (const std::string& failure : report.failures())
    std::fprintf(stderr, "lgh-bench memory: FAILED: %s\n", failure.c_str());
  return report.failures().empty() ? 0 : 1;
}

}  // namespace lgh::bench
