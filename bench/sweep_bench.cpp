#include "bench/sweep_bench.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "bench/progress.h"
#include "bench/reference.h"
#include "bench/stats.h"
#include "bench/table.h"
#include "render/gl/context.h"
#include "render/gl/gl.h"
#include "render/image_compare.h"
#include "render/passes/brute_force_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_volume_pass.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------------
// What to measure.

struct PointSpec {
  float alpha = 1.0f;
  int startLevel = 1, interleave = 1, k = 4;
  bool filter = true;
  bool operator<(const PointSpec& o) const {
    return std::tie(startLevel, alpha, interleave, k, filter) < std::tie(o.startLevel, o.alpha, o.interleave, o.k, o.filter);
  }
  bool operator==(const PointSpec& o) const { return !(*this < o) && !(o < *this); }
};

std::vector<PointSpec> grid(const std::vector<float>& alphas, const std::vector<int>& starts, const std::vector<int>& ns,
                            const std::vector<int>& ks, const std::vector<bool>& filters) {
  std::vector<PointSpec> points;
  for (int s : starts)
    for (float a : alphas)
      for (int n : ns)
        for (int k : ks)
          for (bool f : filters) points.push_back({a, s, n, k, f});
  return points;
}

void appendUnique(std::vector<PointSpec>& to, const std::vector<PointSpec>& from) {
  for (const PointSpec& p : from)
    if (std::find(to.begin(), to.end(), p) == to.end()) to.push_back(p);
}

// The README's sweep: alpha x start level x interleaving (1, 4), without shadows (k = 0: the light
// pass alone, no selection) and with k = 4 and the filter; then one parameter at a time around the
// defaults (alpha 1, S1, 1x1, k 4): k, the filter (raw ratio), 2x2 interleaving.
std::vector<PointSpec> readmePoints() {
  std::vector<PointSpec> points = grid({0.5f, 1.0f, 2.0f, 4.0f}, {0, 1}, {1, 4}, {0, 4}, {true});
  appendUnique(points, grid({1.0f}, {1}, {1}, {1, 2, 8}, {true}));
  appendUnique(points, grid({1.0f}, {1}, {1}, {4}, {false}));
  appendUnique(points, grid({2.0f}, {0}, {1}, {4}, {false}));
  appendUnique(points, grid({1.0f}, {1}, {2}, {4}, {true}));
  appendUnique(points, grid({2.0f}, {0}, {2}, {4}, {true}));
  return points;
}

struct SceneSpec {
  fs::path path;
  std::string camera;  // empty: the scene's first camera
  std::string name;    // file stem, for tables and file names
};

// PATH or PATH@CAMERA (a path that exists as given wins over the split).
SceneSpec parseSceneSpec(const std::string& text) {
  SceneSpec spec;
  const size_t at = text.rfind('@');
  if (at != std::string::npos && !fs::exists(text)) {
    spec.path = text.substr(0, at);
    spec.camera = text.substr(at + 1);
  } else {
    spec.path = text;
  }
  if (!fs::is_regular_file(spec.path)) throw std::runtime_error(spec.path.string() + ": no such scene file");
  spec.path = fs::absolute(spec.path).lexically_normal();
  spec.name = spec.path.stem().string();
  return spec;
}

// ---------------------------------------------------------------------------------------------------
// Measurements.

struct ErrorStats {
  double rmse = kNaN, psnr = kNaN;
};

// Relative RMSE and PSNR of the luminance of estimate(pixel) against the reference over its pixels:
//   rmse = sqrt(sum (a - r)^2 / sum r^2),  psnr = 10 log10(max r^2 / mean (a - r)^2)  (dB; 300 if exact).
// A non-finite estimate makes both NaN.
template <typename Estimate>
ErrorStats errorOver(const reference::ReferenceImage& ref, const std::vector<glm::dvec3>& values, Estimate&& estimate) {
  double squared = 0, norm = 0, peak = 0;
  for (size_t k = 0; k < ref.pixels.size(); ++k) {
    const double r = luminance(values[k]), a = estimate(ref.pixels[k]);
    if (!std::isfinite(a)) return {};
    squared += (a - r) * (a - r);
    norm += r * r;
    peak = std::max(peak, r);
  }
  ErrorStats e;
  e.rmse = std::sqrt(squared / std::max(norm, 1e-300));
  const double mse = squared / double(std::max<size_t>(ref.pixels.size(), 1));
  e.psnr = mse > 0 ? std::min(300.0, 10.0 * std::log10(peak * peak / mse)) : 300.0;
  return e;
}

struct Measurement {
  std::string method;  // lgh, brute_force, brute_force_ratio, brute_force_shadowed, uniform, uniform_shadowed, uniform_ratio
  std::string series;  // grid, baseline, scaling
  RenderSettings settings;
  PointSpec point;
  size_t subsetLights = 0;                              // uniform*: M
  size_t vplTarget = 0, vpls = 0, inputLights = 0;      // the VPLs asked for and made, |S0| (budget: settings.inputLights.vpls)
  std::map<std::string, std::vector<double>> passMs;    // per repeat
  std::vector<double> timeMs, timeUnshadowedMs, frameMs;  // per repeat: the compared times
  double buildMs = kNaN;
  bool extrapolated = false;
  LightStats lights;
  std::vector<double> rmseUnshadowed, psnrUnshadowed, rmseShadowed, psnrShadowed;
  double othersCpu = 0;  // the largest share of the machine other processes took during an accepted sample
  std::string image;  // .npy of the (shadowed) estimate, relative to the output folder
};

double median(const std::vector<double>& v) { return v.empty() ? kNaN : spreadOf(v).median; }

double passMedian(const Measurement& m, const std::string& pass) {
  const auto it = m.passMs.find(pass);
  return it == m.passMs.end() ? kNaN : median(it->second);
}

size_t gridLightsOf(const LightStats& s) {
  size_t n = 0;
  for (size_t l = 1; l < s.lightsPerLevel.size(); ++l) n += s.lightsPerLevel[l];
  return n;
}

struct ReferenceInfo {
  size_t pixels = 0, imagePixels = 0;
  double fraction = 1, seconds = 0;
  std::uint64_t rays = 0, pairs = 0;
  unsigned threads = 0;
  bool cached = false;
  std::string cacheFile;
};

// One scene at one VPL budget: the reference and every measurement against it.
struct Case {
  SceneSpec scene;
  bool scaling = false;  // the time-vs-VPL-count series: no reference, one VPL count per row
  size_t vplTarget = 0, vplBudget = 0, inputLights = 0, vpls = 0, emitterSamples = 0, pointLights = 0;
  int levels = 0;
  double clampDistance = 0;
  RenderSettings base;  // every measurement's settings differ from these only where it says
  std::vector<double> buildMs;
  ReferenceInfo reference;
  std::vector<Measurement> measurements;
};

// ---------------------------------------------------------------------------------------------------
// Small helpers.

// --- Other processes. Times measured minutes apart compare only if nothing else ran meanwhile: a sample
// during which other processes used more than a quarter of the machine is taken again (Sweep::quietly).
struct CpuClock {
  double busyMs = 0;  // every CPU, every process (/proc/stat; 0 where there is none)
  double ownMs = 0;   // this process, all its threads (llvmpipe's included)
  Clock::time_point wall;
};

CpuClock cpuNow() {
  CpuClock c;
  c.wall = Clock::now();
  std::ifstream stat("/proc/stat");
  std::string label;
  unsigned long long v[8] = {};
  if (stat >> label >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7] && label == "cpu")
    c.busyMs = double(v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) * 1000.0 / double(std::max(1L, sysconf(_SC_CLK_TCK)));
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  c.ownMs = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 +
            double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
  return c;
}

// The share of the machine (0..1) other processes used between a and b. /proc/stat counts 10 ms ticks:
// two ticks per core are forgiven as rounding.
double othersShare(const CpuClock& a, const CpuClock& b) {
  if (a.busyMs == 0 && b.busyMs == 0) return 0;
  const double cores = double(std::max(1u, std::thread::hardware_concurrency()));
  const double wall = std::chrono::duration<double, std::milli>(b.wall - a.wall).count();
  const double others = (b.busyMs - a.busyMs) - (b.ownMs - a.ownMs) - 20.0 * cores;
  return std::clamp(others / std::max(wall * cores, 1e-9), 0.0, 1.0);
}

template <typename Fn>
double timedMs(Fn&& fn) {
  glFinish();
  const auto start = Clock::now();
  fn();
  glFinish();
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A uniform random subset of M of the N lights, each scaled by N / M: an unbiased estimate of the sum.
std::vector<gpu::GpuLight> uniformSubset(const std::vector<gpu::GpuLight>& all, size_t m, std::uint32_t seed) {
  m = std::min(m, all.size());
  std::vector<std::uint32_t> index(all.size());
  std::iota(index.begin(), index.end(), 0u);
  std::mt19937 rng(seed);
  for (size_t i = 0; i < m; ++i) std::swap(index[i], index[i + std::uniform_int_distribution<size_t>(0, all.size() - 1 - i)(rng)]);
  const float scale = float(double(all.size()) / double(std::max<size_t>(m, 1)));
  std::vector<gpu::GpuLight> out(m);
  for (size_t i = 0; i < m; ++i) {
    out[i] = all[index[i]];
    out[i].intensity *= scale;
  }
  return out;
}

// A float32 array (height, width, 3) in NumPy's .npy format, for bench/plot_sweep.py.
void writeNpy(const fs::path& path, int width, int height, const std::vector<float>& rgb) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(height) + ", " +
                       std::to_string(width) + ", 3), }";
  const size_t unpadded = 10 + header.size() + 1;
  header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  out.write("\x93NUMPY\x01\x00", 8);
  const std::uint16_t length = std::uint16_t(header.size());
  const char le[2] = {char(length & 0xff), char(length >> 8)};
  out.write(le, 2);
  out.write(header.data(), std::streamsize(header.size()));
  out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

template <typename PixelFn>
void writeImageNpy(const fs::path& path, int width, int height, PixelFn&& pixel) {
  std::vector<float> rgb(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
    const glm::vec3 c = pixel(i);
    for (int k = 0; k < 3; ++k) rgb[3 * i + size_t(k)] = c[k];
  }
  writeNpy(path, width, height, rgb);
}

// The reference images as full frames (zero where the subset has no pixel).
void writeReferenceNpy(const fs::path& path, const reference::ReferenceImage& ref, const std::vector<glm::dvec3>& values) {
  std::vector<float> rgb(size_t(ref.width) * size_t(ref.height) * 3, 0.0f);
  for (size_t k = 0; k < ref.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) rgb[3 * size_t(ref.pixels[k]) + size_t(c)] = float(values[k][c]);
  writeNpy(path, ref.width, ref.height, rgb);
}

std::string settingsLabel(const PointSpec& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "a=%g S%d %dx%d k=%d%s", double(p.alpha), p.startLevel, p.interleave, p.interleave,
                p.k, p.filter || p.k == 0 ? "" : " raw");
  return buffer;
}

std::string fileLabel(const PointSpec& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "a%g_s%d_n%d_k%d_%s", double(p.alpha), p.startLevel, p.interleave, p.k,
                p.filter ? "filter" : "raw");
  return buffer;
}

// Applies NAME=VALUE (render/settings.h) unless the sweep sets that setting itself.
void applySweepSetting(RenderSettings& settings, const std::string& assignment) {
  const std::string name = assignment.substr(0, assignment.find('='));
  for (const char* own : {"width", "height", "camera", "vpls", "alpha", "start-level", "interleave", "shadow-samples",
                          "overdraw", "brute-force"})
    if (name == own)
      throw std::runtime_error("--set " + assignment + ": the sweep sets '" + name + "' itself (use its own option)");
  try {
    applySetting(settings, assignment);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("--set " + assignment + ": " + e.what());
  }
}

// Renders a first frame, raising the VPL budget until the VPLs made meet the target within 2% (light
// paths that leave the scene deposit nothing), as lgh-bench light does. Leaves the budget in `s`.
FrameStats renderToTarget(Renderer& renderer, RenderSettings& s, const CameraView& view, size_t target) {
  s.inputLights.vpls = int(target);
  renderer.setSettings(s);
  FrameStats stats = renderer.render(view);
  for (int attempt = 0; attempt < 4 && stats.lights.vpls > 0 && stats.lights.vpls * 100 < target * 98; ++attempt) {
    s.inputLights.vpls = int(std::min(double(s.inputLights.vpls) * double(target) / double(stats.lights.vpls) * 1.005, 16e6));
    renderer.setSettings(s);
    stats = renderer.render(view);
  }
  return stats;
}

fs::path executableDir() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::current_path() : exe.parent_path();
}

std::string timestamp() {
  const std::time_t now = std::time(nullptr);
  char buffer[64];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M", std::localtime(&now));
  return buffer;
}

// ---------------------------------------------------------------------------------------------------
// The run.

class Sweep {
 public:
  Sweep(const SweepOptions& options, std::vector<PointSpec> points) : options_(options), points_(std::move(points)) {}

  int run();

 private:
  void runCase(const Scene& scene, const SceneGpu& gpu, const reference::OcclusionScene& occlusion, const SceneSpec& spec,
               size_t vplTarget);
  void runScaling(const Scene& scene, const SceneGpu& gpu, const SceneSpec& spec);
  reference::ReferenceImage obtainReference(const reference::OcclusionScene& occlusion, const SceneSpec& spec,
                                            const Renderer& renderer, const std::vector<Light>& lights, Case& c);
  Measurement measureLgh(Renderer& renderer, const CameraView& view, const RenderSettings& base, const PointSpec& point,
                         double buildMs, const reference::ReferenceImage* ref, const fs::path& imageFile);
  std::vector<double> measureBuild(const Renderer& renderer, const Scene& scene);
  void fail(const std::string& message) {
    std::fprintf(stderr, "lgh-bench sweep: check failed: %s\n", message.c_str());
    failures_.push_back(message);
  }
  // Runs sample() (one timed measurement) until other processes stayed under kBusyLimit of the
  // machine while it ran, at most 1 + options.retries times, each retry once the machine has been
  // quiet for a second (waiting up to 2 minutes); returns their share during the last run.
  static constexpr double kBusyLimit = 0.25;
  template <typename Fn>
  double quietly(Fn&& sample) {
    double share = 0;
    for (int attempt = 0; attempt <= options_.retries; ++attempt) {
      if (attempt > 0) {
        ++retries_;
        waitForQuiet();
      }
      const CpuClock before = cpuNow();
      sample();
      share = othersShare(before, cpuNow());
      if (share <= kBusyLimit) break;
    }
    if (share > kBusyLimit) ++contended_;
    return share;
  }
  // Sleeps until other processes used under 10% of the machine for a whole second (at most 2 minutes).
  void waitForQuiet() {
    const auto start = Clock::now();
    while (Clock::now() - start < std::chrono::minutes(2)) {
      const CpuClock before = cpuNow();
      std::this_thread::sleep_for(std::chrono::seconds(1));
      if (othersShare(before, cpuNow()) < 0.1) return;
    }
  }
  void tick() {
    ++done_;
    if (progress_) progress_->update(double(done_));
  }
  void check(const Case& c);
  void printCase(const Case& c) const;
  void writeOutputs() const;

  const SweepOptions& options_;
  std::vector<PointSpec> points_;
  std::unique_ptr<gl::Context> context_;
  fs::path outDir_, imageDir_, cacheDir_;
  std::vector<Case> cases_;
  std::vector<std::string> failures_;
  std::unique_ptr<ProgressBar> progress_;
  size_t done_ = 0;
  size_t retries_ = 0, contended_ = 0;  // samples taken again / still contended after the last try
  std::unique_ptr<LghBuildPass> buildPass_;
  std::unique_ptr<LightVolumePass> lightPass_;
  std::unique_ptr<BruteForcePass> bruteForce_;
};

std::vector<double> Sweep::measureBuild(const Renderer& renderer, const Scene& scene) {
  // The hierarchy over the renderer's S0, built again with the renderer's options (Renderer::buildOptions):
  // in a frame whose lights move, this is paid every frame.
  LghBuildOptions o;
  o.levels = renderer.settings().hierarchy.levels;
  o.eMin = 1e-4 * std::max(double(scene.bounds.diagonal()), 1e-6);
  std::vector<double> samples;
  GpuHierarchy hierarchy;
  const InputLights& in = renderer.inputLights();
  for (int r = 0; r < options_.repeats; ++r) {
    double ms = 0;
    quietly([&] { ms = timedMs([&] { buildPass_->execute(in.lights, in.count, o, hierarchy); }); });
    samples.push_back(ms);
  }
  return samples;
}

Measurement Sweep::measureLgh(Renderer& renderer, const CameraView& view, const RenderSettings& base, const PointSpec& point,
                              double buildMs, const reference::ReferenceImage* ref, const fs::path& imageFile) {
  Measurement m;
  m.method = "lgh";
  m.point = point;
  RenderSettings s = base;
  s.lightPass.alpha = point.alpha;
  s.lightPass.startLevel = point.startLevel;
  s.lightPass.interleave = point.interleave;
  s.shadows.samples = point.k;
  s.filter.passes = point.filter ? base.filter.passes : 0;
  m.settings = s;
  m.buildMs = buildMs;
  // Untimed: the fragment counter (its atomics would be timed too); also the warm-up.
  s.lightPass.overdraw = true;
  renderer.setSettings(s);
  m.lights = renderer.render(view).lights;
  s.lightPass.overdraw = false;
  renderer.setSettings(s);
  for (int r = 0; r < options_.repeats; ++r) {
    FrameStats stats;
    m.othersCpu = std::max(m.othersCpu, quietly([&] { stats = renderer.render(view); }));
    if (stats.nonFinitePixels > 0)
      fail(std::to_string(stats.nonFinitePixels) + " NaN/Inf pixels at " + settingsLabel(point));
    for (const gl::PassTiming& p : stats.passes) m.passMs[p.name].push_back(p.wallMs > 0 ? p.wallMs : p.gpuMs);
    const double lightPass = stats.passMs("interleave split") + stats.passMs("light pass") + stats.passMs("interleave resolve");
    const double shadows = stats.passMs("shadow rays") + stats.passMs("shadow filter");
    m.timeUnshadowedMs.push_back(buildMs + lightPass);
    if (point.k > 0) m.timeMs.push_back(buildMs + lightPass + shadows);
    m.frameMs.push_back(buildMs + stats.totalMs());
    if (ref) {
      const ImageRGBA irradiance = renderer.readImage(Aov::Irradiance);
      const ImageRGBA visibility = renderer.readImage(Aov::Visibility);
      const ErrorStats u = errorOver(*ref, ref->unshadowed, [&](std::uint32_t i) { return luminance(irradiance.pixels[i]); });
      m.rmseUnshadowed.push_back(u.rmse);
      m.psnrUnshadowed.push_back(u.psnr);
      if (point.k > 0 && !ref->shadowed.empty()) {
        const ErrorStats e = errorOver(*ref, ref->shadowed, [&](std::uint32_t i) {
          return luminance(irradiance.pixels[i]) * double(visibility.pixels[i].r);
        });
        m.rmseShadowed.push_back(e.rmse);
        m.psnrShadowed.push_back(e.psnr);
      }
      if (r == options_.repeats - 1 && !imageFile.empty()) {
        writeImageNpy(imageDir_ / imageFile, irradiance.width, irradiance.height, [&](size_t i) {
          return glm::vec3(irradiance.pixels[i]) * (point.k > 0 ? visibility.pixels[i].r : 1.0f);
        });
        m.image = (fs::path("images") / imageFile).string();
      }
    }
  }
  return m;
}

reference::ReferenceImage Sweep::obtainReference(const reference::OcclusionScene& occlusion, const SceneSpec& spec,
                                                 const Renderer& renderer, const std::vector<Light>& lights, Case& c) {
  const RenderSettings& s = renderer.settings();
  reference::ReferenceInput input;
  input.width = s.image.width;
  input.height = s.image.height;
  input.position = renderer.readImage(Aov::Position).pixels;
  input.normal = renderer.readImage(Aov::Normal).pixels;
  input.lights = lights;
  input.clampDistance = renderer.clampDistance();
  size_t valid = 0;
  for (const glm::vec4& p : input.position) valid += p.w > 0 ? 1 : 0;
  const double pairs = double(valid) * double(lights.size());
  double fraction = options_.referencePixels > 0 ? std::min(options_.referencePixels, 1.0)
                                                 : (pairs <= options_.referenceBudget ? 1.0 : options_.referenceBudget / pairs);
  if (fraction < 1.0) fraction = std::max(1e-4, std::round(fraction * 1e4) / 1e4);  // a stable cache key

  // Everything the reference depends on.
  std::error_code error;
  const auto mtime = fs::last_write_time(spec.path, error).time_since_epoch().count();
  std::ostringstream key;
  key << "lgh reference v1\nscene " << spec.path.string() << " mtime " << mtime << " bytes "
      << fs::file_size(spec.path, error) << "\ncamera '" << s.image.camera << "' " << s.image.width << "x" << s.image.height
      << "\nlights vpls " << s.inputLights.vpls << " bounces " << s.inputLights.bounces << " emitter-samples " << s.inputLights.emitterSamples
      << " max-direct-lights " << s.inputLights.maxDirectLights << " seed " << s.inputLights.seed << " count " << lights.size() << " hash "
      << reference::hex64(reference::hashLights(lights)) << "\ngbuffer "
      << reference::hex64(reference::hashBytes(input.normal.data(), input.normal.size() * sizeof(glm::vec4),
                                               reference::hashBytes(input.position.data(),
                                                                    input.position.size() * sizeof(glm::vec4))))
      << "\nclamp " << std::hexfloat << input.clampDistance << std::defaultfloat << "\npixels fraction " << fraction
      << " seed 1\nshadowed 1\n";
  c.reference.fraction = fraction;
  c.reference.imagePixels = size_t(s.image.width) * size_t(s.image.height);
  std::optional<reference::ReferenceImage> ref;
  if (!cacheDir_.empty()) {
    ref = reference::loadReference(cacheDir_, key.str());
    c.reference.cacheFile = (cacheDir_ / reference::cacheFileName(key.str())).string();
  }
  c.reference.cached = bool(ref);
  if (!ref) {
    reference::ReferenceOptions o;
    o.pixelFraction = fraction;
    o.threads = options_.threads;
    o.label = "reference " + spec.name + " " + shortCount(c.vplTarget) + " VPLs";
    ref = reference::computeReference(occlusion, input, o);
    if (!cacheDir_.empty()) reference::storeReference(cacheDir_, key.str(), *ref);
  }
  c.reference.pixels = ref->pixels.size();
  c.reference.seconds = ref->seconds;
  c.reference.rays = ref->rays;
  c.reference.pairs = ref->pairs;
  c.reference.threads = ref->threads;
  return std::move(*ref);
}

void Sweep::runCase(const Scene& scene, const SceneGpu& gpu, const reference::OcclusionScene& occlusion,
                    const SceneSpec& spec, size_t vplTarget) {
  Case c;
  c.scene = spec;
  c.vplTarget = vplTarget;
  RenderSettings base;
  base.image.width = options_.width;
  base.image.height = options_.height;
  base.image.camera = spec.camera;
  for (const std::string& a : options_.set) applySweepSetting(base, a);
  const CameraView view = makeCameraView(resolveCamera(scene, base), base.image.width, base.image.height);
  Renderer renderer(gpu, base);
  const FrameStats first = renderToTarget(renderer, base, view, vplTarget);
  c.vplBudget = size_t(base.inputLights.vpls);
  c.base = base;
  c.inputLights = first.lights.inputLights;
  c.vpls = first.lights.vpls;
  c.emitterSamples = first.lights.emitterSamples;
  c.pointLights = first.lights.pointLights;
  c.levels = first.lights.levels;
  c.clampDistance = renderer.clampDistance();
  const std::vector<gpu::GpuLight> gpuLights = renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count);
  const std::vector<Light> lights = fromGpuLights(gpuLights);

  const reference::ReferenceImage ref = obtainReference(occlusion, spec, renderer, lights, c);
  const bool writeImages = options_.images && ref.full();
  const std::string prefix = spec.name + "_" + shortCount(vplTarget) + "_";
  if (writeImages) {
    writeReferenceNpy(imageDir_ / (prefix + "reference_shadowed.npy"), ref, ref.shadowed);
    writeReferenceNpy(imageDir_ / (prefix + "reference_unshadowed.npy"), ref, ref.unshadowed);
    const ImageRGBA albedo = renderer.readImage(Aov::Albedo);
    writeImageNpy(imageDir_ / (prefix + "albedo.npy"), albedo.width, albedo.height,
                  [&](size_t i) { return glm::vec3(albedo.pixels[i]); });
  }

  c.buildMs = measureBuild(renderer, scene);
  const double buildMs = spreadOf(c.buildMs).median;
  tick();

  // Compile every shader variant the points use before timing anything.
  std::set<std::pair<int, bool>> variants;
  for (const PointSpec& p : points_) variants.insert({p.startLevel, p.k > 0});
  for (const auto& [start, shadows] : variants) {
    RenderSettings s = base;
    s.lightPass.startLevel = start;
    s.shadows.samples = shadows ? 4 : 0;
    renderer.setSettings(s);
    renderer.render(view);
  }

  for (const PointSpec& point : points_) {
    Measurement m = measureLgh(renderer, view, base, point, buildMs, &ref,
                               writeImages ? prefix + fileLabel(point) + ".npy" : std::string());
    m.series = "grid";
    c.measurements.push_back(std::move(m));
    tick();
  }

  // --- Baselines on the same G-buffer and S0.
  const float clamp = renderer.clampDistance();
  const int w = base.image.width, h = base.image.height;
  gl::Texture2D target(w, h, GL_RGBA32F);
  auto readTarget = [&] { return fromGLRows(w, h, target.readRGBA()); };
  const size_t n = gpuLights.size();
  auto rasterizedBruteForce = [&](const gl::Buffer& buffer, size_t count) {
    LightPassOptions o;
    o.pass.bruteForce = true;
    o.clampDistance = clamp;
    LightPassTarget t{renderer.gbuffer().position, renderer.gbuffer().normal, TileLayout::of(1, w, h), target, nullptr, nullptr};
    lightPass_->execute(buffer, count, renderer.hierarchy(), o, t);
  };
  {  // warm-up (compiles the brute-force variant of the light pass)
    const gl::Buffer one = gl::Buffer::fromVector(uniformSubset(gpuLights, 1, 1));
    rasterizedBruteForce(one, 1);
    bruteForce_->execute(renderer.gbuffer(), one, 1, clamp, target, &gpu);
  }
  // Uniform subsampling: M of the N lights, a new random subset each repeat.
  auto uniform = [&](size_t m, bool shadowed) {
    Measurement u;
    u.method = shadowed ? "uniform_shadowed" : "uniform";
    u.series = "baseline";
    u.settings = base;
    u.subsetLights = std::min(m, n);
    for (int r = 0; r < options_.repeats; ++r) {
      const gl::Buffer buffer = gl::Buffer::fromVector(uniformSubset(gpuLights, m, std::uint32_t(1000003u * m + 7919u * unsigned(r) + 17u)));
      if (shadowed) {
        double ms = 0;
        u.othersCpu = std::max(u.othersCpu, quietly([&] {
          ms = timedMs([&] { bruteForce_->execute(renderer.gbuffer(), buffer, u.subsetLights, clamp, target, &gpu); });
        }));
        u.timeMs.push_back(ms);
        u.passMs["brute force shadowed"].push_back(ms);
        const ImageRGBA image = readTarget();
        const ErrorStats e = errorOver(ref, ref.shadowed, [&](std::uint32_t i) { return luminance(image.pixels[i]); });
        u.rmseShadowed.push_back(e.rmse);
        u.psnrShadowed.push_back(e.psnr);
        if (writeImages && r == options_.repeats - 1) {
          const std::string file = prefix + "uniform_shadowed_" + std::to_string(u.subsetLights) + ".npy";
          writeImageNpy(imageDir_ / file, w, h, [&](size_t i) { return glm::vec3(image.pixels[i]); });
          u.image = (fs::path("images") / file).string();
        }
      } else {
        double ms = 0;
        u.othersCpu = std::max(u.othersCpu, quietly([&] { ms = timedMs([&] { rasterizedBruteForce(buffer, u.subsetLights); }); }));
        u.timeUnshadowedMs.push_back(ms);
        u.passMs["light pass"].push_back(ms);
        const ImageRGBA image = readTarget();
        const ErrorStats e = errorOver(ref, ref.unshadowed, [&](std::uint32_t i) { return luminance(image.pixels[i]); });
        u.rmseUnshadowed.push_back(e.rmse);
        u.psnrUnshadowed.push_back(e.psnr);
      }
    }
    tick();
    return u;
  };
  std::vector<Measurement> uniformRuns, uniformShadowedRuns;
  for (size_t m : options_.uniformLights)
    if (m < n) uniformRuns.push_back(uniform(m, false));
  for (size_t m : options_.uniformShadowedLights)
    if (m < n) uniformShadowedRuns.push_back(uniform(m, true));

  // Linear fit t = a + b M over a series, for extrapolating brute force to all N lights.
  auto extrapolate = [&](const std::vector<Measurement>& runs, bool shadowed, size_t to) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0, k = 0;
    for (const Measurement& r : runs) {
      const double x = double(r.subsetLights), y = median(shadowed ? r.timeMs : r.timeUnshadowedMs);
      sx += x, sy += y, sxx += x * x, sxy += x * y, k += 1;
    }
    if (k < 2) return kNaN;
    const double b = (k * sxy - sx * sy) / std::max(k * sxx - sx * sx, 1e-300), a = (sy - b * sx) / k;
    return a + b * double(to);
  };

  // Brute force over all N (RenderSettings::bruteForce: every S0 light full-screen, unshadowed).
  Measurement brute;
  brute.method = "brute_force";
  brute.series = "baseline";
  brute.settings = base;
  brute.settings.lightPass.bruteForce = true;
  brute.settings.shadows.samples = 0;
  brute.subsetLights = n;
  if (n <= options_.bruteForceLimit) {
    renderer.setSettings(brute.settings);
    renderer.render(view);  // warm-up
    for (int r = 0; r < std::min(options_.repeats, 2); ++r) {
      FrameStats stats;
      brute.othersCpu = std::max(brute.othersCpu, quietly([&] { stats = renderer.render(view); }));
      const double ms = stats.passMs("light pass");
      brute.passMs["light pass"].push_back(ms);
      brute.timeUnshadowedMs.push_back(ms);
      const ImageRGBA image = renderer.readImage(Aov::Irradiance);
      const ErrorStats e = errorOver(ref, ref.unshadowed, [&](std::uint32_t i) { return luminance(image.pixels[i]); });
      brute.rmseUnshadowed.push_back(e.rmse);
      brute.psnrUnshadowed.push_back(e.psnr);
    }
  } else {
    brute.extrapolated = true;
    brute.timeUnshadowedMs.push_back(extrapolate(uniformRuns, false, n));
  }
  // The frame's shadow estimate (k importance-picked rays, filtered ratio) on the exact unshadowed sum:
  // the shadow error alone, without the hierarchy's.
  Measurement bruteRatio;
  bruteRatio.method = "brute_force_ratio";
  bruteRatio.series = "baseline";
  bruteRatio.settings = base;
  bruteRatio.settings.lightPass.bruteForce = true;
  bruteRatio.subsetLights = n;
  if (n <= options_.bruteForceLimit && base.shadows.samples > 0) {
    renderer.setSettings(bruteRatio.settings);
    renderer.render(view);  // warm-up (the selection's variant)
    for (int r = 0; r < std::min(options_.repeats, 2); ++r) {
      FrameStats stats;
      bruteRatio.othersCpu = std::max(bruteRatio.othersCpu, quietly([&] { stats = renderer.render(view); }));
      for (const gl::PassTiming& p : stats.passes) bruteRatio.passMs[p.name].push_back(p.wallMs > 0 ? p.wallMs : p.gpuMs);
      bruteRatio.timeMs.push_back(stats.passMs("light pass") + stats.passMs("shadow rays") + stats.passMs("shadow filter"));
      const ImageRGBA irradiance = renderer.readImage(Aov::Irradiance), visibility = renderer.readImage(Aov::Visibility);
      const ErrorStats e = errorOver(ref, ref.shadowed, [&](std::uint32_t i) {
        return luminance(irradiance.pixels[i]) * double(visibility.pixels[i].r);
      });
      bruteRatio.rmseShadowed.push_back(e.rmse);
      bruteRatio.psnrShadowed.push_back(e.psnr);
    }
  }
  tick();
  // Uniform subsampling in the frame's own pipeline: brute force over a fresh set of about M lights
  // (VPL budget and emitter samples scaled by M / N, another seed each repeat: a uniform sample of the
  // same light paths, unbiased like a subset of S0) with the frame's shadow estimate (k
  // importance-picked rays per pixel, the filter). Last: it replaces the renderer's S0.
  std::vector<Measurement> uniformRatioRuns;
  if (base.shadows.samples > 0) {
    bool warm = false;
    for (size_t m : options_.uniformLights) {
      if (m >= n) continue;
      Measurement u;
      u.method = "uniform_ratio";
      u.series = "baseline";
      RenderSettings s = base;
      s.lightPass.bruteForce = true;
      const double f = double(m) / double(n);
      s.inputLights.vpls = std::max(1, int(std::lround(double(base.inputLights.vpls) * f)));
      s.inputLights.emitterSamples = int(std::lround(double(base.inputLights.emitterSamples) * f));
      u.settings = s;
      std::vector<double> made;
      for (int r = warm ? 0 : -1; r < options_.repeats; ++r) {
        s.inputLights.seed = base.inputLights.seed + 101 + r;
        renderer.setSettings(s);
        if (r < 0) {  // the series' first set also compiles its shader variant
          renderer.render(view);
          continue;
        }
        // The frame also makes the new set (its own pass, not counted); a retry renders the same set.
        FrameStats stats;
        u.othersCpu = std::max(u.othersCpu, quietly([&] { stats = renderer.render(view); }));
        for (const gl::PassTiming& p : stats.passes) u.passMs[p.name].push_back(p.wallMs > 0 ? p.wallMs : p.gpuMs);
        u.timeMs.push_back(stats.passMs("light pass") + stats.passMs("shadow rays") + stats.passMs("shadow filter"));
        made.push_back(double(stats.lights.inputLights));
        const ImageRGBA irradiance = renderer.readImage(Aov::Irradiance), visibility = renderer.readImage(Aov::Visibility);
        const ErrorStats e = errorOver(ref, ref.shadowed, [&](std::uint32_t i) {
          return luminance(irradiance.pixels[i]) * double(visibility.pixels[i].r);
        });
        u.rmseShadowed.push_back(e.rmse);
        u.psnrShadowed.push_back(e.psnr);
        const ErrorStats eu = errorOver(ref, ref.unshadowed, [&](std::uint32_t i) { return luminance(irradiance.pixels[i]); });
        u.rmseUnshadowed.push_back(eu.rmse);
        u.psnrUnshadowed.push_back(eu.psnr);
        if (writeImages && r == options_.repeats - 1) {
          const std::string file = prefix + "uniform_ratio_" + std::to_string(m) + ".npy";
          writeImageNpy(imageDir_ / file, w, h, [&](size_t i) { return glm::vec3(irradiance.pixels[i]) * visibility.pixels[i].r; });
          u.image = (fs::path("images") / file).string();
        }
      }
      warm = true;
      u.subsetLights = size_t(std::lround(median(made)));
      uniformRatioRuns.push_back(std::move(u));
      tick();
    }
  }
  // Shadowed brute force (one ray per light and pixel through the GPU BVH): its cost per light from
  // the uniform series, times N.
  Measurement bruteShadowed;
  bruteShadowed.method = "brute_force_shadowed";
  bruteShadowed.series = "baseline";
  bruteShadowed.settings = base;
  bruteShadowed.subsetLights = n;
  bruteShadowed.extrapolated = true;
  bruteShadowed.timeMs.push_back(extrapolate(uniformShadowedRuns, true, n));
  c.measurements.push_back(std::move(brute));
  if (!bruteRatio.timeMs.empty()) c.measurements.push_back(std::move(bruteRatio));
  c.measurements.push_back(std::move(bruteShadowed));
  for (Measurement& m : uniformRuns) c.measurements.push_back(std::move(m));
  for (Measurement& m : uniformShadowedRuns) c.measurements.push_back(std::move(m));
  for (Measurement& m : uniformRatioRuns) c.measurements.push_back(std::move(m));
  for (Measurement& m : c.measurements) {
    m.vplTarget = c.vplTarget;
    m.vpls = c.vpls;
    m.inputLights = c.inputLights;
  }
  check(c);
  cases_.push_back(std::move(c));
}

void Sweep::runScaling(const Scene& scene, const SceneGpu& gpu, const SceneSpec& spec) {
  Case c;
  c.scene = spec;
  c.scaling = true;
  RenderSettings base;
  base.image.width = options_.width;
  base.image.height = options_.height;
  base.image.camera = spec.camera;
  for (const std::string& a : options_.set) applySweepSetting(base, a);
  c.base = base;
  const CameraView view = makeCameraView(resolveCamera(scene, base), base.image.width, base.image.height);
  double bruteMsPerLight = kNaN;
  for (size_t target : options_.scalingVpls) {
    Renderer renderer(gpu, base);
    const FrameStats first = renderToTarget(renderer, base, view, target);
    auto tag = [&](Measurement& m) {
      m.vplTarget = target;
      m.vpls = first.lights.vpls;
      m.inputLights = first.lights.inputLights;
    };
    const std::vector<double> build = measureBuild(renderer, scene);
    for (int n : {1, 4}) {
      Measurement m = measureLgh(renderer, view, base, PointSpec{1.0f, 1, n, 4, true}, spreadOf(build).median, nullptr, {});
      m.series = "scaling";
      tag(m);
      c.measurements.push_back(std::move(m));
      tick();
    }
    Measurement brute;
    brute.method = "brute_force";
    brute.series = "scaling";
    brute.settings = base;
    brute.settings.lightPass.bruteForce = true;
    brute.settings.shadows.samples = 0;
    brute.subsetLights = first.lights.inputLights;
    tag(brute);
    if (first.lights.inputLights <= options_.bruteForceLimit) {
      renderer.setSettings(brute.settings);
      renderer.render(view);
      for (int r = 0; r < std::min(options_.repeats, 2); ++r) {
        double ms = 0;
        brute.othersCpu = std::max(brute.othersCpu, quietly([&] { ms = renderer.render(view).passMs("light pass"); }));
        brute.passMs["light pass"].push_back(ms);
        brute.timeUnshadowedMs.push_back(ms);
      }
      bruteMsPerLight = median(brute.timeUnshadowedMs) / double(std::max<size_t>(first.lights.inputLights, 1));
    } else {
      brute.extrapolated = true;
      brute.timeUnshadowedMs.push_back(bruteMsPerLight * double(first.lights.inputLights));
    }
    c.measurements.push_back(std::move(brute));
    tick();
  }
  cases_.push_back(std::move(c));
}

void Sweep::check(const Case& c) {
  const std::string where = c.scene.name + " " + shortCount(c.vplTarget) + " VPLs: ";
  for (const Measurement& m : c.measurements) {
    for (const auto* errors : {&m.rmseUnshadowed, &m.rmseShadowed})
      for (double e : *errors)
        if (!std::isfinite(e)) fail(where + m.method + " " + settingsLabel(m.point) + ": non-finite error");
    // The GL brute force is the exact unshadowed sum, as the reference: they must agree.
    if (m.method == "brute_force" && !m.rmseUnshadowed.empty() && !(median(m.rmseUnshadowed) < 1e-4))
      fail(where + "GL brute force vs the Embree reference: relative RMSE " + std::to_string(median(m.rmseUnshadowed)) +
           " (> 1e-4)");
  }
  // Starting at S0, a larger alpha weights S0 more: the unshadowed error must fall (1x1, so the
  // irradiance is deterministic; 1% slack for the float sums).
  std::map<std::tuple<int, int, bool>, std::vector<std::pair<float, double>>> series;
  for (const Measurement& m : c.measurements)
    if (m.method == "lgh" && m.point.startLevel == 0 && m.point.interleave == 1 && !m.rmseUnshadowed.empty())
      series[{m.point.k, m.point.interleave, m.point.filter}].push_back({m.point.alpha, median(m.rmseUnshadowed)});
  for (auto& [key, values] : series) {
    std::sort(values.begin(), values.end());
    for (size_t i = 1; i < values.size(); ++i)
      if (!(values[i].second <= values[i - 1].second * 1.01))
        fail(where + "start level 0: the unshadowed error does not fall from alpha " + std::to_string(values[i - 1].first) +
             " (" + std::to_string(values[i - 1].second) + ") to " + std::to_string(values[i].first) + " (" +
             std::to_string(values[i].second) + ")");
  }
}

nlohmann::json settingsJson(RenderSettings s) {
  nlohmann::json j;
  visitSettings(s, [&](auto& value, const SettingInfo& info) { j[info.name] = value; });
  return j;
}

std::string fmt(double v, const char* format = "%.4g") {
  if (!std::isfinite(v)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

void Sweep::printCase(const Case& c) const {
  if (c.scaling) {
    std::printf("\n%s: time and overdraw vs VPL count (alpha 1, S1, k 4), %d x %d\n", c.scene.name.c_str(),
                options_.width, options_.height);
    TextTable table({"input lights", "method", "tiles", "L", "grid lights", "fragments/px", "light pass ms", "frame ms"});
    for (const Measurement& m : c.measurements)
      table.addRow({formatCount(m.inputLights), m.method + (m.extrapolated ? " (extrapolated)" : ""),
                    m.method == "lgh" ? std::to_string(m.point.interleave) + "x" + std::to_string(m.point.interleave) : "-",
                    m.method == "lgh" ? std::to_string(m.lights.levels) : "-",
                    m.method == "lgh" ? formatCount(gridLightsOf(m.lights)) : "-",
                    m.method == "lgh" ? formatMs(m.lights.rasterizedPerPixel) : "-",
                    formatMs(median(m.timeUnshadowedMs) - (std::isfinite(m.buildMs) ? m.buildMs : 0.0)),
                    formatMs(median(m.frameMs))});
    table.print(stdout);
    return;
  }
  std::printf("\n%s%s%s, %d x %d, %s VPLs (budget %s): %s input lights (%s VPLs, %s emitter samples, %s point lights), "
              "L = %d, clamp %.3g\n",
              c.scene.name.c_str(), c.scene.camera.empty() ? "" : " @ ", c.scene.camera.c_str(), options_.width,
              options_.height, shortCount(c.vplTarget).c_str(), formatCount(c.vplBudget).c_str(), formatCount(c.inputLights).c_str(),
              formatCount(c.vpls).c_str(), formatCount(c.emitterSamples).c_str(), formatCount(c.pointLights).c_str(),
              c.levels, c.clampDistance);
  std::printf("reference: %s of %s pixels (fraction %.4g), %s rays, %s, %.1f M rays/s on %u threads%s; build %s ms\n",
              formatCount(c.reference.pixels).c_str(), formatCount(c.reference.imagePixels).c_str(), c.reference.fraction,
              formatCount(size_t(c.reference.rays)).c_str(), ProgressBar::formatSeconds(c.reference.seconds).c_str(),
              double(c.reference.rays) / std::max(c.reference.seconds, 1e-9) / 1e6, c.reference.threads,
              c.reference.cached ? " (from the cache)" : "", formatSpread(spreadOf(c.buildMs)).c_str());
  TextTable table({"method", "settings", "frag/px", "time ms (shadowed)", "time ms (unshadowed)", "rmse unsh.",
                   "rmse shadowed", "psnr sh."});
  for (const Measurement& m : c.measurements) {
    std::string settings = m.method == "lgh" ? settingsLabel(m.point) : "M = " + formatCount(m.subsetLights);
    if (m.extrapolated) settings += " (extrapolated)";
    table.addRow({m.method, settings, m.method == "lgh" ? formatMs(m.lights.rasterizedPerPixel) : "-",
                  m.timeMs.empty() ? "-" : formatSpread(spreadOf(m.timeMs)),
                  m.timeUnshadowedMs.empty() ? "-" : formatSpread(spreadOf(m.timeUnshadowedMs)),
                  fmt(median(m.rmseUnshadowed)), fmt(median(m.rmseShadowed)), fmt(median(m.psnrShadowed), "%.1f")});
  }
  table.print(stdout);
}

void Sweep::writeOutputs() const {
  // CSV: one row per measurement, medians over the repeats ("" where a value does not apply).
  const fs::path csvPath = outDir_ / "sweep.csv", jsonPath = outDir_ / "sweep.json";
  std::ofstream csv(csvPath.string() + ".tmp");
  if (!csv) throw std::runtime_error(csvPath.string() + ": cannot open for writing");
  auto num = [](double v) {
    if (!std::isfinite(v)) return std::string();
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return std::string(buffer);
  };
  csv << "scene,camera,width,height,vpl_target,vpl_budget,vpls,input_lights,method,series,alpha,start_level,interleave,shadow_samples,"
         "filter,subset_lights,levels,grid_lights,fragments_per_pixel,shaded_per_pixel,time_ms,time_ms_min,time_ms_max,"
         "time_unshadowed_ms,build_ms,light_pass_ms,interleave_ms,shadow_rays_ms,shadow_filter_ms,frame_ms,extrapolated,"
         "rmse_unshadowed,psnr_unshadowed,rmse_shadowed,psnr_shadowed,rmse_shadowed_min,rmse_shadowed_max,"
         "reference_pixels,others_cpu,image\n";
  for (const Case& c : cases_)
    for (const Measurement& m : c.measurements) {
      const bool lgh = m.method == "lgh";
      const Spread t = spreadOf(m.timeMs), rs = spreadOf(m.rmseShadowed);
      csv << c.scene.name << "," << c.scene.camera << "," << options_.width << "," << options_.height << ","
          << m.vplTarget << "," << m.settings.inputLights.vpls << "," << m.vpls << "," << m.inputLights << "," << m.method << ","
          << m.series << "," << (lgh ? num(m.point.alpha) : "") << "," << (lgh ? std::to_string(m.point.startLevel) : "")
          << "," << (lgh ? std::to_string(m.point.interleave) : "") << "," << (lgh ? std::to_string(m.point.k) : "") << ","
          << (lgh && m.point.k > 0 ? (m.point.filter ? "on" : "off") : "") << "," << (lgh ? "" : std::to_string(m.subsetLights)) << ","
          << (lgh ? std::to_string(m.lights.levels) : "") << "," << (lgh ? std::to_string(gridLightsOf(m.lights)) : "")
          << "," << (lgh ? num(m.lights.rasterizedPerPixel) : "") << "," << (lgh ? num(m.lights.shadedPerPixel) : "")
          << "," << (m.timeMs.empty() ? "" : num(t.median)) << "," << (m.timeMs.empty() ? "" : num(t.min)) << ","
          << (m.timeMs.empty() ? "" : num(t.max)) << "," << num(median(m.timeUnshadowedMs)) << "," << num(m.buildMs)
          << "," << num(passMedian(m, "light pass")) << ","
          << (lgh && m.point.interleave > 1
                  ? num(passMedian(m, "interleave split") + passMedian(m, "interleave resolve"))
                  : "")
          << "," << num(passMedian(m, "shadow rays")) << "," << num(passMedian(m, "shadow filter")) << ","
          << num(median(m.frameMs)) << "," << (m.extrapolated ? 1 : 0) << "," << num(median(m.rmseUnshadowed)) << ","
          << num(median(m.psnrUnshadowed)) << "," << num(rs.median) << "," << num(median(m.psnrShadowed)) << ","
          << (m.rmseShadowed.empty() ? "" : num(rs.min)) << "," << (m.rmseShadowed.empty() ? "" : num(rs.max)) << ","
          << (c.scaling ? "" : std::to_string(c.reference.pixels)) << "," << num(std::round(m.othersCpu * 100) / 100) << ","
          << m.image << "\n";
    }
  csv.close();
  if (!csv) throw std::runtime_error(csvPath.string() + ": write failed");
  fs::rename(csvPath.string() + ".tmp", csvPath);

  // JSON: everything, with every repeat and every render setting.
  using nlohmann::json;
  // Five significant digits (timings and errors carry no more), null for NaN: keeps the file small.
  auto significant = [](double x) {
    if (!std::isfinite(x)) return json(nullptr);
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.5g", x);
    return json(std::strtod(buffer, nullptr));
  };
  auto finite = [&](const std::vector<double>& v) {
    json a = json::array();
    for (double x : v) a.push_back(significant(x));
    return a;
  };
  json root;
  root["generated"] = timestamp();
  root["device"] = context_->description();
  root["hardware_threads"] = std::thread::hardware_concurrency();
  root["width"] = options_.width;
  root["height"] = options_.height;
  root["repeats"] = options_.repeats;
  root["preset"] = options_.preset;
  root["definitions"] = {
      {"time_ms", "shadowed estimate: LGH build + interleave split + light pass + resolve + shadow rays + filter; "
                  "uniform_shadowed: compute brute force with one ray per subset light and pixel; brute_force_ratio and "
                  "uniform_ratio: the rasterized brute-force light pass over all / about M lights (a fresh set: VPL budget "
                  "and emitter samples scaled by M/N) with the frame's shadow rays and filter"},
      {"time_unshadowed_ms", "unshadowed estimate: LGH build + split + light pass + resolve; brute_force and uniform: "
                             "the rasterized brute-force light pass (every light full-screen)"},
      {"rmse", "relative RMSE of luminance, sqrt(sum (a - r)^2 / sum r^2), over the reference's pixels"},
      {"psnr", "10 log10(max r^2 / mean (a - r)^2) over the reference's pixels, luminance, dB"},
      {"compared", "irradiance before albedo: Aov::Irradiance (unshadowed) and Aov::Irradiance x Aov::Visibility (shadowed)"},
      {"others_cpu", "the largest share of the machine other processes took during a sample that was kept (a sample "
                     "during which they took more than 25% is taken again once they are quiet, up to 3 times)"}};
  for (const Case& c : cases_) {
    json jc;
    jc["scene"] = c.scene.path.string();
    jc["name"] = c.scene.name;
    jc["camera"] = c.scene.camera;
    jc["series"] = c.scaling ? "scaling" : "grid";
    jc["base_settings"] = settingsJson(c.base);
    if (!c.scaling) {
      jc["vpl_target"] = c.vplTarget;
      jc["vpl_budget"] = c.vplBudget;
      jc["input_lights"] = c.inputLights;
      jc["vpls"] = c.vpls;
      jc["emitter_samples"] = c.emitterSamples;
      jc["point_lights"] = c.pointLights;
      jc["levels"] = c.levels;
      jc["clamp_distance"] = c.clampDistance;
      jc["build_ms"] = finite(c.buildMs);
      jc["reference"] = {{"pixels", c.reference.pixels},     {"image_pixels", c.reference.imagePixels},
                         {"fraction", c.reference.fraction}, {"seconds", significant(c.reference.seconds)},
                         {"rays", c.reference.rays},         {"pixel_light_pairs", c.reference.pairs},
                         {"threads", c.reference.threads},   {"from_cache", c.reference.cached},
                         {"cache_file", c.reference.cacheFile}};
    }
    for (const Measurement& m : c.measurements) {
      json jm;
      jm["method"] = m.method;
      jm["series"] = m.series;
      // Only what differs from the case's base settings (which are listed in full once).
      json settings = json::object();
      const json base = settingsJson(c.base), own = settingsJson(m.settings);
      for (const auto& [name, value] : own.items())
        if (base[name] != value) settings[name] = value;
      jm["settings"] = settings;
      if (m.method != "lgh") jm["subset_lights"] = m.subsetLights;
      jm["vpl_target"] = m.vplTarget;
      jm["vpls"] = m.vpls;
      jm["extrapolated"] = m.extrapolated;
      jm["others_cpu"] = significant(m.othersCpu);
      if (m.method == "lgh") {
        jm["levels"] = m.lights.levels;
        jm["lights_per_level"] = m.lights.lightsPerLevel;
        jm["input_lights"] = m.lights.inputLights;
        jm["fragments_per_pixel"] = significant(m.lights.rasterizedPerPixel);
        jm["shaded_per_pixel"] = significant(m.lights.shadedPerPixel);
        jm["max_fragments"] = m.lights.maxRasterized;
        jm["build_ms"] = significant(m.buildMs);
      }
      json passes;
      for (const auto& [name, samples] : m.passMs) passes[name] = finite(samples);
      jm["pass_ms"] = passes;
      jm["time_ms"] = finite(m.timeMs);
      jm["time_unshadowed_ms"] = finite(m.timeUnshadowedMs);
      jm["frame_ms"] = finite(m.frameMs);
      jm["rmse_unshadowed"] = finite(m.rmseUnshadowed);
      jm["psnr_unshadowed"] = finite(m.psnrUnshadowed);
      jm["rmse_shadowed"] = finite(m.rmseShadowed);
      jm["psnr_shadowed"] = finite(m.psnrShadowed);
      if (!m.image.empty()) jm["image"] = m.image;
      jc["measurements"].push_back(jm);
    }
    root["cases"].push_back(jc);
  }
  root["failures"] = failures_;
  root["samples_retaken"] = retries_;
  root["samples_contended"] = contended_;
  std::ofstream jsonFile(jsonPath.string() + ".tmp");
  if (!jsonFile) throw std::runtime_error(jsonPath.string() + ": cannot open for writing");
  jsonFile << root.dump() << "\n";
  jsonFile.close();
  if (!jsonFile) throw std::runtime_error(jsonPath.string() + ": write failed");
  fs::rename(jsonPath.string() + ".tmp", jsonPath);
}

int Sweep::run() {
  // Everything that can be wrong with the input is found before the first frame.
  std::vector<SceneSpec> specs;
  for (const std::string& s : options_.scenes) specs.push_back(parseSceneSpec(s));
  if (specs.empty()) throw std::runtime_error("no scene: give --scene PATH[@CAMERA] or a --preset");
  {
    RenderSettings s;
    for (const std::string& a : options_.set) applySweepSetting(s, a);
  }
  std::vector<Scene> scenes;
  for (const SceneSpec& spec : specs) {
    scenes.push_back(loadScene(spec.path));
    RenderSettings s;
    s.image.camera = spec.camera;
    resolveCamera(scenes.back(), s);  // throws, naming the cameras there are, for a wrong name
  }
  outDir_ = options_.outDir;
  imageDir_ = outDir_ / "images";
  fs::create_directories(options_.images ? imageDir_ : outDir_);
  if (options_.cacheDir != "none") cacheDir_ = options_.cacheDir.empty() ? executableDir() / "reference-cache" : fs::path(options_.cacheDir);

  gl::ContextOptions contextOptions;
  contextOptions.backend = gl::parseBackend(options_.backend);
  context_ = gl::Context::create(contextOptions);
  buildPass_ = std::make_unique<LghBuildPass>(GLAD_GL_NV_shader_atomic_float != 0);
  lightPass_ = std::make_unique<LightVolumePass>(GLAD_GL_NV_shader_atomic_float != 0);
  bruteForce_ = std::make_unique<BruteForcePass>();

  std::fprintf(stderr, "lgh-bench sweep: %zu scene%s x %zu VPL budget%s, %zu points each, %d repeats, %d x %d, %s\n",
               specs.size(), specs.size() == 1 ? "" : "s", options_.vpls.size(), options_.vpls.size() == 1 ? "" : "s",
               points_.size(), options_.repeats, options_.width, options_.height, context_->description().c_str());
  std::fprintf(stderr, "  output: %s; reference cache: %s\n", outDir_.string().c_str(),
               cacheDir_.empty() ? "none" : cacheDir_.string().c_str());
  const size_t perCase = 2 + points_.size() + 2 * options_.uniformLights.size() + options_.uniformShadowedLights.size();
  const size_t total = specs.size() * (options_.vpls.size() * perCase + options_.scalingVpls.size() * 3);
  progress_ = std::make_unique<ProgressBar>("sweep", double(total));

  for (size_t i = 0; i < specs.size(); ++i) {
    const SceneGpu gpu(scenes[i]);
    const reference::OcclusionScene occlusion(scenes[i].positions, scenes[i].indices);
    for (size_t vpls : options_.vpls) runCase(scenes[i], gpu, occlusion, specs[i], vpls);
    if (!options_.scalingVpls.empty()) runScaling(scenes[i], gpu, specs[i]);
  }
  progress_->finish();

  std::printf("lgh-bench sweep: %s, %s; %d repeats per point (median)\n", timestamp().c_str(),
              context_->description().c_str(), options_.repeats);
  std::printf("time ms (shadowed) = LGH build + light pass (+ interleaving) + shadow rays + filter; (unshadowed) = build "
              "+ light pass; errors: relative RMSE of luminance against the Embree reference\n");
  for (const Case& c : cases_) printCase(c);
  writeOutputs();
  std::printf("\n%zu timed samples taken again because other processes used more than %.0f%% of the machine; %zu "
              "still contended after %d tries\n",
              retries_, 100 * kBusyLimit, contended_, options_.retries + 1);
  std::printf("wrote %s and %s\n", (outDir_ / "sweep.csv").string().c_str(), (outDir_ / "sweep.json").string().c_str());
  if (!failures_.empty()) {
    std::fprintf(stderr, "lgh-bench sweep: %zu check%s failed:\n", failures_.size(), failures_.size() == 1 ? "" : "s");
    for (const std::string& f : failures_) std::fprintf(stderr, "  %s\n", f.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options) {
  CLI::App* command = app.add_subcommand(
      "sweep", "error vs time over a parameter grid against the exact (Embree) reference, with brute-force and "
               "uniform-subsampling baselines; writes CSV, JSON and images for bench/plot_sweep.py");
  options.command = command;
  const std::map<std::string, size_t> thousands{{"K", 1000}, {"M", 1000000}};
  command->add_option("--preset", options.preset,
                      "readme: the README's sweep (sponza_sun@atrium and cornell_emissive, 10K and 100K VPLs, "
                      "~20 min); smoke: a tiny run for ctest. Options given explicitly override the preset's")
      ->check(CLI::IsMember({"readme", "smoke"}));
  command->add_option("--scene", options.scenes, "glTF scene, PATH or PATH@CAMERA (repeatable)");
  command->add_option("--width", options.width, "image width")->check(CLI::Range(8, 8192))->capture_default_str();
  command->add_option("--height", options.height, "image height")->check(CLI::Range(8, 8192))->capture_default_str();
  command->add_option("--vpls", options.vpls,
                      "VPL counts, comma-separated (1K, 1M allowed); the budget is raised until the VPLs made reach each")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->check(CLI::Range(size_t(1), size_t(16000000)))
      ->capture_default_str();
  command->add_option("--alpha", options.alphas, "alphas, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(0.25, 16.0))
      ->capture_default_str();
  command->add_option("--start-level", options.startLevels, "start levels (0, 1), comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(0, 1))
      ->capture_default_str();
  command->add_option("--interleave", options.interleave, "interleaving factors n (n x n tiles), comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  command->add_option("--shadow-samples", options.shadowSamples, "k, comma-separated (0-16; 0: unshadowed, no selection)")
      ->delimiter(',')
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  command->add_option("--filter", options.filter, "shadow filter: on, off, or on,off")
      ->delimiter(',')
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  command->add_option("--repeats", options.repeats, "timed frames per point")->check(CLI::Range(1, 100))->capture_default_str();
  command->add_option("--reference-pixels", options.referencePixels,
                      "fraction of the pixels the reference computes (0: all, unless that exceeds --reference-budget)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--reference-budget", options.referenceBudget,
                      "pixel-light pairs above which the automatic reference takes a random pixel subset")
      ->check(CLI::Range(1e3, 1e13))
      ->capture_default_str();
  command->add_option("--uniform-lights", options.uniformLights, "uniform subsampling, unshadowed: subset sizes M")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--uniform-shadowed-lights", options.uniformShadowedLights,
                      "uniform subsampling with exact visibility: subset sizes M")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--brute-force-limit", options.bruteForceLimit,
                      "measure the full brute force up to this many input lights, else extrapolate")
      ->transform(CLI::AsNumberWithUnit(thousands))
      ->capture_default_str();
  command->add_option("--scaling-vpls", options.scalingVpls,
                      "also time and count overdraw at these VPL counts (alpha 1, S1, k 4; no error; 0: none)")
      ->delimiter(',')
      ->transform(CLI::AsNumberWithUnit(thousands));
  command->add_option("--out", options.outDir, "output folder (default: bench/results for --preset readme, else sweep-results)");
  command->add_option("--cache-dir", options.cacheDir, "reference cache (default: reference-cache beside lgh-bench; none: off)");
  command->add_option("--images", options.images, "write .npy images for the image strip (full references only)")
      ->capture_default_str();
  command->add_option("--threads", options.threads, "reference threads (0: all)")->capture_default_str();
  command->add_option("--retries", options.retries,
                      "take a timed sample again, once the machine is quiet (waiting up to 2 min), up to this many "
                      "times while other processes use more than 25% of the machine")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  command->add_option("--backend", options.backend, "OpenGL context")->capture_default_str();
  command->add_option("--set", options.set, "NAME=VALUE: any other render setting for every point (e.g. bounces=1)");
  return command;
}

int runSweepBench(SweepOptions options) {
  auto given = [&](const char* name) { return options.command && options.command->count(name) > 0; };
  std::vector<PointSpec> points;
  const fs::path sharedScenes = fs::path(LGH_SHARED_SCENES_DIR).lexically_normal();
  if (options.preset == "readme") {
    if (!given("--scene")) {
      for (const char* s : {"sponza_sun/sponza_sun.gltf", "cornell_emissive/cornell_emissive.gltf"})
        if (!fs::exists(sharedScenes / s))
          throw std::runtime_error("--preset readme needs " + (sharedScenes / s).string() + " (../shared/scenes beside the checkout)");
      options.scenes = {(sharedScenes / "sponza_sun/sponza_sun.gltf").string() + "@atrium",
                        (sharedScenes / "cornell_emissive/cornell_emissive.gltf").string()};
    }
    if (!given("--vpls")) options.vpls = {10000, 100000};
    if (!given("--scaling-vpls")) options.scalingVpls = {1000, 10000, 100000, 1000000};
    if (!given("--out")) options.outDir = (fs::path(LGH_SOURCE_DIR) / "bench" / "results").string();
    const bool gridGiven = given("--alpha") || given("--start-level") || given("--interleave") ||
                           given("--shadow-samples") || given("--filter");
    if (!gridGiven) points = readmePoints();
  } else if (options.preset == "smoke") {
    if (!given("--scene")) options.scenes = {(fs::path(LGH_DATA_DIR) / "cornell_box.gltf").string()};
    if (!given("--width")) options.width = 64;
    if (!given("--height")) options.height = 36;
    if (!given("--vpls")) options.vpls = {1000};
    if (!given("--alpha")) options.alphas = {0.5f, 2.0f};
    if (!given("--start-level")) options.startLevels = {0};
    if (!given("--interleave")) options.interleave = {1};
    if (!given("--repeats")) options.repeats = 1;
    if (!given("--uniform-lights")) options.uniformLights = {16, 64};
    if (!given("--uniform-shadowed-lights")) options.uniformShadowedLights = {2, 4};
    if (!given("--images")) options.images = false;
    if (!given("--retries")) options.retries = 0;  // ctest runs tests side by side: times are not the point
  }
  if (options.outDir.empty()) options.outDir = "sweep-results";
  options.scalingVpls.erase(std::remove(options.scalingVpls.begin(), options.scalingVpls.end(), size_t(0)),
                            options.scalingVpls.end());  // --scaling-vpls 0: none
  if (points.empty()) {
    std::vector<bool> filters;
    for (const std::string& f : options.filter) filters.push_back(f == "on");
    points = grid(options.alphas, options.startLevels, options.interleave, options.shadowSamples, filters);
  }
  for (size_t m : options.uniformLights)
    if (m == 0) throw std::runtime_error("--uniform-lights: subset sizes must be >= 1");
  for (size_t m : options.uniformShadowedLights)
    if (m == 0) throw std::runtime_error("--uniform-shadowed-lights: subset sizes must be >= 1");
  return Sweep(options, std::move(points)).run();
}

}  // namespace lgh::bench
