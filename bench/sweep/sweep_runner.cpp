#include "bench/sweep/sweep_runner.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <tuple>

#include "bench/common/bytes.h"
#include "bench/common/npy.h"
#include "bench/common/ranks.h"
#include "bench/common/stats.h"
#include "bench/common/table.h"
#include "bench/sweep/sweep_reference.h"
#include "render/image_compare.h"

namespace lgh::bench {
namespace {

namespace fs = std::filesystem;

// A uniform random subset of M of the N lights, each scaled by N / M: an unbiased estimate of the sum.
std::vector<gpu::GpuLight> uniformSubset(const std::vector<gpu::GpuLight>& all, size_t m, std::uint32_t seed) {
  m = std::min(m, all.size());
  std::vector<std::uint32_t> index(all.size());
  std::iota(index.begin(), index.end(), 0u);
  std::mt19937 rng(seed);
  for (size_t i = 0; i < m; ++i)
    std::swap(index[i], index[i + std::uniform_int_distribution<size_t>(0, all.size() - 1 - i)(rng)]);
  const float scale = float(double(all.size()) / double(std::max<size_t>(m, 1)));
  std::vector<gpu::GpuLight> out(m);
  for (size_t i = 0; i < m; ++i) {
    out[i] = all[index[i]];
    out[i].intensity *= scale;
  }
  return out;
}

// The reference images as full frames (zero where the subset has no pixel).
void writeReferenceNpy(const fs::path& path, const reference::ReferenceImage& ref,
                       const std::vector<glm::dvec3>& values) {
  std::vector<float> rgb(size_t(ref.width) * size_t(ref.height) * 3, 0.0f);
  for (size_t k = 0; k < ref.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) rgb[3 * size_t(ref.pixels[k]) + size_t(c)] = float(values[k][c]);
  writeNpy(path, ref.width, ref.height, rgb);
}

// The estimate a measurement's error and image are of: the irradiance, times the visibility if given.
glm::vec3 estimate(const ImageRGBA& irradiance, const ImageRGBA* visibility, size_t i) {
  return glm::vec3(irradiance.pixels[i]) * (visibility ? visibility->pixels[i].r : 1.0f);
}

// The shadowed brute-force frame's time: the light pass over every light, the shadow rays and the filter.
double bruteForceRatioMs(const FrameStats& stats) {
  return stats.passMs(passes::kLightPass) + stats.passMs(passes::kShadowRays) + stats.passMs(passes::kShadowFilter);
}

Measurement baseline(const char* method, const RenderSettings& settings, size_t subsetLights) {
  Measurement m;
  m.method = method;
  m.series = "baseline";
  m.settings = settings;
  m.subsetLights = subsetLights;
  return m;
}

}  // namespace

struct SweepRunner::CaseImages {
  fs::path dir;
  std::string prefix;  // scene_VPLs_
  // Writes the estimate as images/<prefix><name>.npy and records it in m.
  void write(Measurement& m, const std::string& name, const ImageRGBA& irradiance, const ImageRGBA* visibility) const {
    const std::string file = prefix + name + ".npy";
    writeImageNpy(dir / file, irradiance.width, irradiance.height,
                  [&](size_t i) { return estimate(irradiance, visibility, i); });
    m.image = (fs::path("images") / file).string();
  }
};

SweepRunner::SweepRunner(const Ranks& ranks, const SweepOptions& options, std::vector<PointSpec> points,
                         fs::path imageDir, fs::path cacheDir)
    : ranks_(ranks),
      options_(options),
      points_(std::move(points)),
      imageDir_(std::move(imageDir)),
      cacheDir_(std::move(cacheDir)),
      sampler_(options.retries),
      buildPass_(GLAD_GL_NV_shader_atomic_float != 0),
      lightPass_(GLAD_GL_NV_shader_atomic_float != 0) {}

size_t SweepRunner::workPerScene() const {
  const size_t perCase = 2 + points_.size() + 2 * options_.uniformLights.size() + options_.uniformShadowedLights.size();
  return options_.vpls.size() * perCase + options_.scalingVpls.size() * 3;
}

RenderSettings SweepRunner::baseSettings(const SceneSpec& spec) const {
  RenderSettings base = options_.settings;
  base.image.camera = spec.camera;
  return base;
}

void SweepRunner::fail(const std::string& message) {
  std::fprintf(stderr, "lgh-bench sweep: check failed: %s\n", message.c_str());
  failures_.push_back(message);
}

bool SweepRunner::mine(size_t point) const { return int(point % size_t(ranks_.size())) == ranks_.rank(); }

void SweepRunner::tick() {
  ++done_;
  if (progress_) progress_->update(double(done_));
}

FrameStats SweepRunner::timedFrame(BenchRenderer& bench, Measurement& m, int frames) {
  // Each repeat is a new estimate: the frames before the timed one build its history, untimed.
  bench.renderer().restartAccumulation();
  for (int f = 1; f < frames; ++f) bench.renderer().render(bench.view());
  FrameStats stats;
  m.othersCpu = std::max(m.othersCpu, sampler_.sample([&] { stats = bench.renderer().render(bench.view()); }));
  return stats;
}

std::vector<double> SweepRunner::measureStructureBuild(const Renderer& renderer, bool lightTree) {
  // Built again over the renderer's S0 (the Renderer builds it only when S0 changes): in a frame whose
  // lights move, this is paid every frame. Same options as the renderer's build.
  const LghBuildOptions o = renderer.buildOptions();
  const InputLights& in = renderer.inputLights();
  GpuHierarchy hierarchy;
  GpuLightTree tree;
  auto build = [&] {
    if (lightTree)
      treePass_.execute(in.lights, in.count, tree);
    else
      buildPass_.execute(in.lights, in.count, o, hierarchy);
  };
  build();  // warm-up: the shaders compile at their first dispatch
  std::vector<double> samples;
  for (int r = 0; r < options_.repeats; ++r) {
    double ms = 0;
    sampler_.sample([&] { ms = timedMs(build); });
    samples.push_back(ms);
  }
  return samples;
}

// Compiles every shader variant the points use before anything is timed.
void SweepRunner::compileVariants(BenchRenderer& bench, const RenderSettings& base) {
  std::set<std::pair<int, bool>> variants;
  for (const PointSpec& p : points_) {
    if (p.lightcuts) continue;
    variants.insert({p.startLevel, p.k > 0});
  }
  for (const auto& [start, shadows] : variants) {
    RenderSettings s = base;
    s.lightPass.startLevel = start;
    s.shadows.samples = shadows ? 4 : 0;
    bench.render(s);
  }
  for (const PointSpec& p : points_)
    if (p.lightcuts) {
      bench.render(p.applied(base));
      break;
    }
}

// The LGH's points: time = the hierarchy's build + split + light pass + resolve + shadow targets, rays and
// filter (unshadowed: without the last three); error = its irradiance (times its filtered visibility).
// The lightcuts' points: time = the tree's build + cuts + sampling + irradiance filter; error = their
// shadowed irradiance (filtered when the point says so). Both against the reference.
Measurement SweepRunner::measurePoint(BenchRenderer& bench, const RenderSettings& base, const PointSpec& point,
                                      double structureMs, const reference::ReferenceImage* ref,
                                      const CaseImages* images) {
  Measurement m;
  m.method = point.lightcuts ? methods::kRtslc : methods::kLgh;
  m.point = point;
  bench.renderer().restartRandomSequence();  // the same frames on any rank (gatherPoints)
  RenderSettings s = point.applied(base);
  m.settings = s;
  m.buildMs = structureMs;
  // Untimed: the LGH's fragment counter (its atomics would be timed too); also the warm-up.
  s.lightPass.overdraw = !point.lightcuts;
  m.lights = bench.render(s).lights;
  s.lightPass.overdraw = false;
  bench.renderer().setSettings(s);
  const bool shadowed = point.lightcuts || point.k > 0;
  for (int r = 0; r < options_.repeats; ++r) {
    const FrameStats stats = timedFrame(bench, m, point.frames);
    if (stats.nonFinitePixels > 0)
      fail(std::to_string(stats.nonFinitePixels) + " NaN/Inf pixels at " + m.method + " " + settingsLabel(point));
    m.addPassTimes(stats);
    if (!point.lightcuts) m.timeUnshadowedMs.push_back(structureMs + lightPassMs(stats));
    if (shadowed) m.timeMs.push_back(structureMs + indirectMs(stats));
    m.frameMs.push_back(structureMs + stats.totalMs());
    if (!ref) continue;
    // The lightcuts' irradiance is shadowed already: their visibility reads 1.
    const ImageRGBA irradiance = bench.renderer().readImage(Aov::Irradiance);
    const ImageRGBA visibility = bench.renderer().readImage(Aov::Visibility);
    if (!point.lightcuts) m.addUnshadowedError(unshadowedError(*ref, irradiance));
    if (shadowed && !ref->shadowed.empty()) {
      m.addShadowedError(shadowedError(*ref, irradiance, &visibility));
      if (!point.lightcuts) m.rmseExactRatio.push_back(exactRatioError(*ref, irradiance).rmse);
    }
    if (r == options_.repeats - 1 && images)
      images->write(m, fileLabel(point), irradiance, shadowed ? &visibility : nullptr);
  }
  return m;
}

// Brute force over all S0 lights (RenderSettings::lightPass.bruteForce: every light full-screen,
// unshadowed), measured up to options.bruteForceLimit lights; beyond, marked extrapolated with no time.
Measurement SweepRunner::measureBruteForce(BenchRenderer& bench, const RenderSettings& base, size_t lights,
                                           const reference::ReferenceImage* ref, const char* series) {
  Measurement brute = baseline(methods::kBruteForce, base, lights);
  brute.series = series;
  brute.settings.lightPass.bruteForce = true;
  brute.settings.shadows.samples = 0;
  if (lights > options_.bruteForceLimit) {
    brute.extrapolated = true;
    return brute;
  }
  bench.render(brute.settings);  // warm-up
  for (int r = 0; r < std::min(options_.repeats, 2); ++r) {
    const double ms = timedFrame(bench, brute).passMs(passes::kLightPass);
    brute.passMs[passes::kLightPass].push_back(ms);
    brute.timeUnshadowedMs.push_back(ms);
    if (ref) brute.addUnshadowedError(unshadowedError(*ref, bench.renderer().readImage(Aov::Irradiance)));
  }
  return brute;
}

// The baselines of one case, on the Renderer's G-buffer and S0: uniform subsampling (M of the N
// lights through the light pass, or through the shadowed compute brute force), brute force over all N
// (measured, or extrapolated from the uniform series), and the frame's shadow estimate on the exact
// unshadowed sum and on fresh sets of about M lights.
class SweepRunner::Baselines {
 public:
  Baselines(SweepRunner& runner, BenchRenderer& bench, const SceneGpu& gpu, const RenderSettings& base,
            const std::vector<gpu::GpuLight>& lights, const reference::ReferenceImage& ref, const CaseImages* images)
      : runner_(runner),
        bench_(bench),
        renderer_(bench.renderer()),
        gpu_(gpu),
        base_(base),
        ref_(ref),
        images_(images),
        lights_(lights),
        clamp_(renderer_.clampDistance()),
        target_({"bench", "subsampling target", kImageSize}, base.image.width, base.image.height, GL_RGBA32F) {}

  // Every baseline, in the order of the outputs.
  std::vector<Measurement> measure();

 private:
  void warmUp();
  void rasterizedBruteForce(const gl::Buffer& lights, size_t count);
  ImageRGBA readTarget() const { return fromGLRows(target_.width(), target_.height(), target_.readRGBA()); }
  Measurement uniform(size_t m, bool shadowed);
  Measurement bruteForceRatio();
  std::vector<Measurement> uniformRatio();
  double extrapolate(const std::vector<Measurement>& runs, bool shadowed) const;

  SweepRunner& runner_;
  BenchRenderer& bench_;
  Renderer& renderer_;
  const SceneGpu& gpu_;
  const RenderSettings& base_;
  const reference::ReferenceImage& ref_;
  const CaseImages* images_;
  const std::vector<gpu::GpuLight>& lights_;  // S0
  const float clamp_;
  gl::Texture2D target_;  // the baselines' image when the Renderer does not draw them
};

std::vector<Measurement> SweepRunner::Baselines::measure() {
  const size_t n = lights_.size();
  renderer_.restartRandomSequence();  // whatever points rank 0 measured before
  warmUp();
  std::vector<Measurement> uniformRuns, uniformShadowedRuns;
  for (size_t m : runner_.options_.uniformLights)
    if (m < n) uniformRuns.push_back(uniform(m, false));
  for (size_t m : runner_.options_.uniformShadowedLights)
    if (m < n) uniformShadowedRuns.push_back(uniform(m, true));
  Measurement brute = runner_.measureBruteForce(bench_, base_, n, &ref_, "baseline");
  if (brute.extrapolated) brute.timeUnshadowedMs.push_back(extrapolate(uniformRuns, false));
  Measurement bruteRatio = bruteForceRatio();
  runner_.tick();
  std::vector<Measurement> uniformRatioRuns = uniformRatio();  // last: it replaces the renderer's S0
  // Shadowed brute force (one ray per light and pixel through the GPU BVH): its cost per light from the
  // uniform series, times N.
  Measurement bruteShadowed = baseline(methods::kBruteForceShadowed, base_, n);
  bruteShadowed.extrapolated = true;
  bruteShadowed.timeMs.push_back(extrapolate(uniformShadowedRuns, true));

  std::vector<Measurement> all;
  all.push_back(std::move(brute));
  if (!bruteRatio.timeMs.empty()) all.push_back(std::move(bruteRatio));
  all.push_back(std::move(bruteShadowed));
  for (auto* runs : {&uniformRuns, &uniformShadowedRuns, &uniformRatioRuns})
    for (Measurement& m : *runs) all.push_back(std::move(m));
  return all;
}

// Compiles the brute-force variant of the light pass and the compute brute force.
void SweepRunner::Baselines::warmUp() {
  const gl::Buffer one = gl::Buffer::fromVector({"bench", "lights"}, uniformSubset(lights_, 1, 1));
  rasterizedBruteForce(one, 1);
  runner_.bruteForce_.execute({renderer_.gbuffer(), one, 1, &gpu_}, clamp_, target_);
}

// The light pass in brute-force mode (every light full-screen) over `lights`, into target_.
void SweepRunner::Baselines::rasterizedBruteForce(const gl::Buffer& lights, size_t count) {
  LightPassOptions o;
  o.pass.bruteForce = true;
  o.clampDistance = clamp_;
  const int w = base_.image.width, h = base_.image.height;
  LightPassTarget t{
      renderer_.gbuffer().position, renderer_.gbuffer().normal, TileLayout::of(1, w, h), target_, nullptr, nullptr};
  runner_.lightPass_.execute({lights, count, renderer_.hierarchy()}, o, t);
}

// Uniform subsampling: M of the N lights, a new random subset each repeat; unshadowed through the light
// pass, or shadowed through the compute brute force (exact visibility per light).
Measurement SweepRunner::Baselines::uniform(size_t m, bool shadowed) {
  Measurement u =
      baseline(shadowed ? methods::kUniformShadowed : methods::kUniform, base_, std::min(m, lights_.size()));
  const int repeats = runner_.options_.repeats;
  for (int r = 0; r < repeats; ++r) {
    const std::uint32_t seed = std::uint32_t(1000003u * m + 7919u * unsigned(r) + 17u);
    const gl::Buffer buffer = gl::Buffer::fromVector({"bench", "lights"}, uniformSubset(lights_, m, seed));
    double ms = 0;
    u.othersCpu = std::max(u.othersCpu, runner_.sampler_.sample([&] {
      ms = timedMs([&] {
        if (shadowed)
          runner_.bruteForce_.execute({renderer_.gbuffer(), buffer, u.subsetLights, &gpu_}, clamp_, target_);
        else
          rasterizedBruteForce(buffer, u.subsetLights);
      });
    }));
    const ImageRGBA image = readTarget();
    if (shadowed) {
      u.timeMs.push_back(ms);
      u.passMs[kBruteForceShadowedPass].push_back(ms);
      u.addShadowedError(shadowedError(ref_, image, nullptr));
      if (images_ && r == repeats - 1)
        images_->write(u, "uniform_shadowed_" + std::to_string(u.subsetLights), image, nullptr);
    } else {
      u.timeUnshadowedMs.push_back(ms);
      u.passMs[passes::kLightPass].push_back(ms);
      u.addUnshadowedError(unshadowedError(ref_, image));
    }
  }
  runner_.tick();
  return u;
}

// The frame's shadow estimate (k importance-picked rays, filtered ratio) on the exact unshadowed sum:
// the shadow error alone, without the hierarchy's. Not measured (no times) beyond the brute-force limit.
Measurement SweepRunner::Baselines::bruteForceRatio() {
  Measurement ratio = baseline(methods::kBruteForceRatio, base_, lights_.size());
  ratio.settings.lightPass.bruteForce = true;
  if (lights_.size() > runner_.options_.bruteForceLimit || base_.shadows.samples <= 0) return ratio;
  bench_.render(ratio.settings);  // warm-up (the selection's variant)
  for (int r = 0; r < std::min(runner_.options_.repeats, 2); ++r) {
    const FrameStats stats = runner_.timedFrame(bench_, ratio);
    ratio.addPassTimes(stats);
    ratio.timeMs.push_back(bruteForceRatioMs(stats));
    const ImageRGBA irradiance = renderer_.readImage(Aov::Irradiance),
                    visibility = renderer_.readImage(Aov::Visibility);
    ratio.addShadowedError(shadowedError(ref_, irradiance, &visibility));
  }
  return ratio;
}

// Uniform subsampling in the frame's own pipeline: brute force over a fresh set of about M lights (VPL
// budget and emitter samples scaled by M / N, another seed each repeat: a uniform sample of the same
// light paths, unbiased like a subset of S0) with the frame's shadow estimate (k importance-picked rays
// per pixel, the filter). Replaces the renderer's S0.
std::vector<Measurement> SweepRunner::Baselines::uniformRatio() {
  std::vector<Measurement> runs;
  if (base_.shadows.samples <= 0) return runs;
  const size_t n = lights_.size();
  const int repeats = runner_.options_.repeats;
  for (size_t m : runner_.options_.uniformLights) {
    if (m >= n) continue;
    RenderSettings s = base_;
    s.lightPass.bruteForce = true;
    const double f = double(m) / double(n);
    s.inputLights.vpls = std::max(1, int(std::lround(double(base_.inputLights.vpls) * f)));
    s.inputLights.emitterSamples = int(std::lround(double(base_.inputLights.emitterSamples) * f));
    Measurement u = baseline(methods::kUniformRatio, s, 0);
    std::vector<double> made;
    for (int r = runs.empty() ? -1 : 0; r < repeats; ++r) {
      s.inputLights.seed = base_.inputLights.seed + 101 + r;
      if (r < 0) {  // the series' first set also compiles its shader variant
        bench_.render(s);
        continue;
      }
      // The frame also makes the new set (its own pass, not counted); a retry renders the same set.
      renderer_.setSettings(s);
      const FrameStats stats = runner_.timedFrame(bench_, u);
      u.addPassTimes(stats);
      u.timeMs.push_back(bruteForceRatioMs(stats));
      made.push_back(double(stats.lights.inputLights));
      const ImageRGBA irradiance = renderer_.readImage(Aov::Irradiance),
                      visibility = renderer_.readImage(Aov::Visibility);
      u.addShadowedError(shadowedError(ref_, irradiance, &visibility));
      u.addUnshadowedError(unshadowedError(ref_, irradiance));
      if (images_ && r == repeats - 1) images_->write(u, "uniform_ratio_" + std::to_string(m), irradiance, &visibility);
    }
    u.subsetLights = size_t(std::lround(median(made)));
    runs.push_back(std::move(u));
    runner_.tick();
  }
  return runs;
}

// A baseline's time over all N lights from its series over subsets (a linear fit in M).
double SweepRunner::Baselines::extrapolate(const std::vector<Measurement>& runs, bool shadowed) const {
  std::vector<std::pair<double, double>> points;
  for (const Measurement& r : runs)
    points.push_back({double(r.subsetLights), median(shadowed ? r.timeMs : r.timeUnshadowedMs)});
  return extrapolateLinear(points, double(lights_.size()));
}

Case SweepRunner::runCase(const SceneGpu& gpu, const reference::OcclusionScene& occlusion, const SceneSpec& spec,
                          size_t vplTarget) {
  Case c;
  c.scene = spec;
  c.vplTarget = vplTarget;
  RenderSettings base = baseSettings(spec);
  BenchRenderer bench(gpu, base);
  const FrameStats first = bench.renderToVplTarget(base, vplTarget);
  Renderer& renderer = bench.renderer();
  c.vplBudget = size_t(base.inputLights.vpls);
  c.base = base;
  c.inputLights = first.lights.inputLights;
  c.vpls = first.lights.vpls;
  c.emitterSamples = first.lights.emitterSamples;
  c.pointLights = first.lights.pointLights;
  c.levels = first.lights.levels;
  c.clampDistance = renderer.clampDistance();
  const std::vector<gpu::GpuLight> lights =
      renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count);

  ReferenceRequest request;
  request.pixels = options_.referencePixels;
  request.budget = options_.referenceBudget;
  request.run.tileSize = options_.tileSize;
  request.run.threads = options_.threads;
  request.run.cacheDir = cacheDir_;
  request.run.label = "reference " + spec.name + " " + shortCount(vplTarget) + " VPLs";
  const reference::ReferenceImage ref = obtainReference(
      ranks_, occlusion, spec, base, referenceInput(renderer, fromGpuLights(lights)), request, c.reference);
  const CaseImages images{imageDir_, spec.name + "_" + shortCount(vplTarget) + "_"};
  const bool writeImages = options_.images && ref.full();
  if (writeImages && ranks_.root()) {
    writeReferenceNpy(images.dir / (images.prefix + "reference_shadowed.npy"), ref, ref.shadowed);
    writeReferenceNpy(images.dir / (images.prefix + "reference_unshadowed.npy"), ref, ref.unshadowed);
    const ImageRGBA albedo = renderer.readImage(Aov::Albedo);
    writeImageNpy(images.dir / (images.prefix + "albedo.npy"), albedo.width, albedo.height,
                  [&](size_t i) { return glm::vec3(albedo.pixels[i]); });
  }

  c.buildMs = measureStructureBuild(renderer, false);
  const double buildMs = spreadOf(c.buildMs).median;
  if (std::any_of(points_.begin(), points_.end(), [](const PointSpec& p) { return p.lightcuts; }))
    c.treeBuildMs = measureStructureBuild(renderer, true);
  const double treeBuildMs = c.treeBuildMs.empty() ? kNaN : spreadOf(c.treeBuildMs).median;
  tick();
  compileVariants(bench, base);
  std::vector<std::pair<size_t, Measurement>> measured;
  for (size_t i = 0; i < points_.size(); ++i) {
    if (!mine(i)) continue;
    const PointSpec& point = points_[i];
    const CaseImages* pointImages = writeImages ? &images : nullptr;
    Measurement m = measurePoint(bench, base, point, point.lightcuts ? treeBuildMs : buildMs, &ref, pointImages);
    m.series = "grid";
    measured.emplace_back(i, std::move(m));
    tick();
  }
  gatherPoints(c, std::move(measured));
  if (!ranks_.root()) return c;
  for (Measurement& m : Baselines(*this, bench, gpu, base, lights, ref, writeImages ? &images : nullptr).measure())
    c.measurements.push_back(std::move(m));
  for (Measurement& m : c.measurements) {
    m.vplTarget = c.vplTarget;
    m.vpls = c.vpls;
    m.inputLights = c.inputLights;
  }
  check(c);
  return c;
}

Case SweepRunner::runScaling(const SceneGpu& gpu, const SceneSpec& spec) {
  Case c;
  c.scene = spec;
  c.scaling = true;
  RenderSettings base = baseSettings(spec);
  c.base = base;
  double bruteMsPerLight = kNaN;
  for (size_t target : options_.scalingVpls) {
    BenchRenderer bench(gpu, base);
    const FrameStats first = bench.renderToVplTarget(base, target);
    const size_t inputLights = first.lights.inputLights;
    const double buildMs = spreadOf(measureStructureBuild(bench.renderer(), false)).median;
    std::vector<Measurement> rows;
    for (int n : {1, 4}) {
      rows.push_back(measurePoint(bench, base, PointSpec{1.0f, 1, n, 4, true}, buildMs, nullptr, nullptr));
      rows.back().series = "scaling";
      tick();
    }
    Measurement brute = measureBruteForce(bench, base, inputLights, nullptr, "scaling");
    if (brute.extrapolated)
      brute.timeUnshadowedMs.push_back(bruteMsPerLight * double(inputLights));
    else
      bruteMsPerLight = median(brute.timeUnshadowedMs) / double(std::max<size_t>(inputLights, 1));
    rows.push_back(std::move(brute));
    tick();
    for (Measurement& m : rows) {
      m.vplTarget = target;
      m.vpls = first.lights.vpls;
      m.inputLights = inputLights;
      c.measurements.push_back(std::move(m));
    }
  }
  return c;
}

namespace {

// What a rank measured at a grid point, exactly (the point and its settings are known to rank 0).
void writeMeasured(ByteWriter& w, const Measurement& m) {
  w.string(m.method);
  w.string(m.series);
  w.pod(std::uint64_t(m.passMs.size()));
  for (const auto& [pass, ms] : m.passMs) {
    w.string(pass);
    w.vector(ms);
  }
  for (const std::vector<double>* v : {&m.timeMs, &m.timeUnshadowedMs, &m.frameMs, &m.rmseUnshadowed, &m.psnrUnshadowed,
                                       &m.rmseShadowed, &m.psnrShadowed, &m.maeShadowed, &m.rmseExactRatio})
    w.vector(*v);
  w.pod(m.buildMs);
  w.pod(m.extrapolated);
  w.pod(m.othersCpu);
  w.string(m.image);
  const LightStats& l = m.lights;
  for (size_t v : {l.inputLights, l.pointLights, l.emitterSamples, l.vpls}) w.pod(std::uint64_t(v));
  w.pod(l.levels);
  w.vector(l.lightsPerLevel);
  w.pod(l.rasterizedPerPixel);
  w.pod(l.shadedPerPixel);
  w.pod(l.maxRasterized);
}

bool readMeasured(ByteReader& r, Measurement& m) {
  std::uint64_t passes = 0;
  if (!r.string(m.method) || !r.string(m.series) || !r.pod(passes)) return false;
  for (std::uint64_t i = 0; i < passes; ++i) {
    std::string pass;
    if (!r.string(pass) || !r.vector(m.passMs[pass])) return false;
  }
  for (std::vector<double>* v : {&m.timeMs, &m.timeUnshadowedMs, &m.frameMs, &m.rmseUnshadowed, &m.psnrUnshadowed,
                                 &m.rmseShadowed, &m.psnrShadowed, &m.maeShadowed, &m.rmseExactRatio})
    if (!r.vector(*v)) return false;
  if (!r.pod(m.buildMs) || !r.pod(m.extrapolated) || !r.pod(m.othersCpu) || !r.string(m.image)) return false;
  LightStats& l = m.lights;
  for (size_t* v : {&l.inputLights, &l.pointLights, &l.emitterSamples, &l.vpls}) {
    std::uint64_t value = 0;
    if (!r.pod(value)) return false;
    *v = size_t(value);
  }
  return r.pod(l.levels) && r.vector(l.lightsPerLevel) && r.pod(l.rasterizedPerPixel) && r.pod(l.shadedPerPixel) &&
         r.pod(l.maxRasterized);
}

}  // namespace

void SweepRunner::gatherPoints(Case& c, std::vector<std::pair<size_t, Measurement>> measured) {
  // Each rank sends its points (index + what it measured) and the checks that failed on it.
  ByteWriter w;
  w.pod(std::uint64_t(failures_.size() - failuresSent_));
  for (size_t i = failuresSent_; i < failures_.size(); ++i) w.string(failures_[i]);
  failuresSent_ = failures_.size();
  for (const auto& [index, m] : measured) {
    w.pod(std::uint64_t(index));
    writeMeasured(w, m);
  }
  const std::vector<std::string> fromRanks =
      ranks_.distributed() ? ranks_.gather(w.bytes()) : std::vector<std::string>();
  if (!ranks_.root()) return;
  std::vector<std::optional<Measurement>> byPoint(points_.size());
  for (auto& [index, m] : measured) byPoint[index] = std::move(m);
  for (size_t rank = 1; rank < fromRanks.size(); ++rank) {
    ByteReader r(fromRanks[rank]);
    std::uint64_t failures = 0;
    bool ok = r.pod(failures);
    for (std::uint64_t i = 0; ok && i < failures; ++i) {
      std::string f;
      ok = r.string(f);
      if (ok) failures_.push_back("rank " + std::to_string(rank) + ": " + f);
    }
    while (ok && !r.atEnd()) {
      std::uint64_t index = 0;
      Measurement m;
      ok = r.pod(index) && index < points_.size() && readMeasured(r, m);
      if (!ok) break;
      m.point = points_[size_t(index)];
      m.settings = m.point.applied(c.base);
      byPoint[size_t(index)] = std::move(m);
    }
    if (!ok) throw std::runtime_error("sweep: malformed measurements from rank " + std::to_string(rank));
  }
  for (size_t i = 0; i < byPoint.size(); ++i) {
    if (!byPoint[i]) throw std::runtime_error("sweep: no rank measured point " + settingsLabel(points_[i]));
    c.measurements.push_back(std::move(*byPoint[i]));
    if (!mine(i)) tick();
  }
}

void SweepRunner::check(const Case& c) {
  const std::string where = c.scene.name + " " + shortCount(c.vplTarget) + " VPLs: ";
  for (const Measurement& m : c.measurements) {
    for (const auto* errors : {&m.rmseUnshadowed, &m.rmseShadowed})
      for (double e : *errors)
        if (!std::isfinite(e)) fail(where + m.method + " " + settingsLabel(m.point) + ": non-finite error");
    // The GL brute force is the exact unshadowed sum, as the reference: they must agree.
    if (m.method == methods::kBruteForce && !m.rmseUnshadowed.empty() && !(median(m.rmseUnshadowed) < 1e-4))
      fail(where + "GL brute force vs the Embree reference: relative RMSE " + std::to_string(median(m.rmseUnshadowed)) +
           " (> 1e-4)");
  }
  // Starting at S0, a larger alpha weights S0 more: the unshadowed error must fall (1x1, so the
  // irradiance is deterministic; 1% slack for the float sums).
  std::map<std::tuple<int, int, bool>, std::vector<std::pair<float, double>>> series;
  for (const Measurement& m : c.measurements)
    if (m.lgh() && m.point.startLevel == 0 && m.point.interleave == 1 && !m.rmseUnshadowed.empty())
      series[{m.point.k, m.point.interleave, m.point.filter}].push_back({m.point.alpha, median(m.rmseUnshadowed)});
  for (auto& [key, values] : series) {
    std::sort(values.begin(), values.end());
    for (size_t i = 1; i < values.size(); ++i)
      if (!(values[i].second <= values[i - 1].second * 1.01))
        fail(where + "start level 0: the unshadowed error does not fall from alpha " +
             std::to_string(values[i - 1].first) + " (" + std::to_string(values[i - 1].second) + ") to " +
             std::to_string(values[i].first) + " (" + std::to_string(values[i].second) + ")");
  }
}

}  // namespace lgh::bench
