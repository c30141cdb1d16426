#include "bench/engine/motion_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "bench/common/light_source.h"
#include "bench/common/ranks.h"
#include "bench/common/table.h"
#include "bench/engine/motion_error.h"
#include "bench/reference/reference.h"
#include "bench/sweep/sweep_reference.h"
#include "bench/sweep/sweep_stats.h"
#include "render/image_compare.h"
#include "render/passes/lgh_build_pass.h"
#include "render/scene/scripted_motion.h"

namespace lgh::bench {
namespace {

// One way of rendering the sequence, with its own renderer (and so its own history).
struct Configuration {
  std::string name;
  RenderSettings settings;
  bool redrawVpls = false;  // the VPLs drawn from new random numbers every frame (seed + frame)
};

std::vector<Configuration> configurations(const MotionBenchOptions& options) {
  const RenderSettings base = options.render.settings;
  const auto make = [&](std::string name, IndirectMethod method, bool history, HistoryMotion motion,
                        bool redraw = false) {
    Configuration c{std::move(name), base, redraw};
    c.settings.indirectMethod = method;
    c.settings.accumulation.enabled = history;
    c.settings.accumulation.motion = motion;
    return c;
  };
  std::vector<Configuration> list = {
      make("lgh, no history", IndirectMethod::Lgh, false, HistoryMotion::Restart),
      make("lgh, ratio history (paper)", IndirectMethod::Lgh, true, HistoryMotion::Ratio),
      make("lgh, tested history", IndirectMethod::Lgh, true, HistoryMotion::Gradient),
      make("lgh, no history, VPLs redrawn", IndirectMethod::Lgh, false, HistoryMotion::Restart, true),
  };
  if (options.lightcutSamples > 0) {
    list.push_back(make("lightcuts, no history", IndirectMethod::Rtslc, false, HistoryMotion::Restart));
    list.push_back(make("lightcuts, tested history", IndirectMethod::Rtslc, true, HistoryMotion::Gradient));
    // Their paper's: SVGF's temporal accumulation, alpha = 0.2 (Lin & Yuksel 2020, Fig. 9), the history
    // kept whatever moved, as an exponential moving average of 5 frames.
    list.push_back(make("lightcuts, SVGF history (paper)", IndirectMethod::Rtslc, true, HistoryMotion::Keep));
    list.back().settings.accumulation.maxFrames = 5;
    for (size_t c = list.size() - 3; c < list.size(); ++c) list[c].settings.rtslc.samples = options.lightcutSamples;
  }
  return list;
}

// A frame's estimate: the unshadowed irradiance and the visibility the image multiplies it by (the
// lightcuts' irradiance is shadowed already: their visibility reads 1), read back once.
struct FrameImages {
  ImageRGBA irradiance, visibility;
  explicit FrameImages(const Renderer& renderer)
      : irradiance(renderer.readImage(Aov::Irradiance)), visibility(renderer.readImage(Aov::Visibility)) {}
};

// The estimate at the reference's pixels: the irradiance's luminance I and the visibility V.
struct PixelValues {
  std::vector<double> irradiance, visibility;
  double shadowed(size_t k) const { return irradiance[k] * visibility[k]; }
};

PixelValues valuesAtPixels(const FrameImages& images, const reference::ReferenceImage& ref) {
  PixelValues values;
  for (const std::uint32_t p : ref.pixels) {
    values.irradiance.push_back(luminance(images.irradiance.pixels[p]));
    values.visibility.push_back(double(images.visibility.pixels[p].r));
  }
  return values;
}

struct Series {
  std::vector<double> error, temporal, ms;
  std::vector<double> irradianceTemporal, visibilityTemporal;  // the temporal error's two parts
  std::vector<double> last;                                    // the previous frame's values at the reference's pixels
  ErrorParts lastParts;
};

double rms(const std::vector<double>& v, size_t from = 0) {
  double sum = 0;
  for (size_t i = from; i < v.size(); ++i) sum += v[i] * v[i];
  return v.size() > from ? std::sqrt(sum / double(v.size() - from)) : kNaN;
}
double mean(const std::vector<double>& v, size_t from = 0) {
  double sum = 0;
  for (size_t i = from; i < v.size(); ++i) sum += v[i];
  return v.size() > from ? sum / double(v.size() - from) : kNaN;
}

// The reference's shadowed irradiance and the image's side by side, tone-mapped, for the animated figure.
void writeSideBySide(const std::filesystem::path& file, const reference::ReferenceImage& ref, const FrameImages& images,
                     float exposure) {
  ImageRGBA both;
  both.width = 2 * ref.width;
  both.height = ref.height;
  both.pixels.assign(size_t(both.width) * size_t(both.height), glm::vec4(0, 0, 0, 1));
  for (size_t k = 0; k < ref.pixels.size(); ++k) {
    const size_t x = ref.pixels[k] % size_t(ref.width), y = ref.pixels[k] / size_t(ref.width);
    both.pixels[y * size_t(both.width) + x] = glm::vec4(glm::vec3(ref.shadowed[k]), 1.0f);
    both.pixels[y * size_t(both.width) + size_t(ref.width) + x] =
        glm::vec4(glm::vec3(images.irradiance.pixels[ref.pixels[k]]) * images.visibility.pixels[ref.pixels[k]].r, 1.0f);
  }
  writeImage(file, both, exposure, ToneMap::Aces);
}

// The scene as the sequence moves it, on every rank alike: the animation at each frame's time and the
// scripted steps (pure functions of the frame), and the occluders the reference traces.
class SequenceScene {
 public:
  SequenceScene(Scene& scene, const MotionBenchOptions& options, const std::filesystem::path& path)
      : scene_(scene),
        options_(options),
        motion_(parseScriptedMotion(options.sunStep, options.pointStep, options.orbitStep)),
        startLights_(scene.lights) {
    if (scene.animation.empty() && motion_.empty())
      throw std::invalid_argument(path.string() +
                                  " has no animation: give --sun-step, --point-step or --orbit-step to move it");
    start_ = options.startTime >= 0 ? options.startTime : scene.animation.start;
  }
  double time(int frame) const { return start_ + double(frame) / options_.fps; }
  // Poses frame `frame`: what moved, and the camera it is seen through.
  PoseChange pose(int frame, Camera& camera) {
    PoseChange change = poseScene(scene_, time(frame));
    camera = resolveCamera(scene_, options_.render.settings);
    change.merge(applyScriptedMotion(motion_, frame, startLights_, scene_, camera));
    if (!occlusion_ || change.geometry)
      occlusion_ = std::make_unique<reference::OcclusionScene>(scene_.positions, scene_.indices);
    return change;
  }
  // The occluders of the frame posed last; the same on every rank, or the run ends (checkSameOccluders).
  const reference::OcclusionScene& occlusion() const { return *occlusion_; }
  void checkSameOccluders(const Ranks& ranks, int frame) const {
    std::string root = reference::hex64(occlusion_->contentHash());
    const std::string mine = root;
    ranks.broadcast(root);
    if (mine != root)
      ranks.abort("lgh-bench motion: frame " + std::to_string(frame) + ": this rank's occluders (" + mine +
                  ") are not rank 0's (" + root + ")");
  }

 private:
  Scene& scene_;
  const MotionBenchOptions& options_;
  ScriptedMotion motion_;
  std::vector<PunctualLight> startLights_;
  double start_ = 0;
  std::unique_ptr<reference::OcclusionScene> occlusion_;
};

std::string ranksLine(const Ranks& ranks) {
  return ranks.distributed() ? std::to_string(ranks.size()) + " ranks (the references shared)" : "one rank";
}

ReferenceRequest referenceRequest(const MotionBenchOptions& options) {
  ReferenceRequest request;
  request.pixels = options.referencePixels;
  request.run.cacheDir =
      options.referenceCache.empty() ? defaultReferenceCache() : std::filesystem::path(options.referenceCache);
  request.run.progress = false;
  return request;
}

// Ranks other than 0 render nothing (no GL): each moves its own copy of the scene as rank 0 does and
// computes its share of every frame's reference tiles (obtainReference is collective; rank 0 sends the
// frame's G-buffer and lights).
void shareTheReferences(const MotionBenchOptions& options, const Ranks& ranks) {
  std::string why;
  const std::filesystem::path path = chooseRenderScene(options.render.scene, why);
  Scene scene = loadScene(path);
  SequenceScene sequence(scene, options, path);
  const SceneSpec spec{path, options.render.settings.image.camera, path.stem().string()};
  ReferenceRequest request = referenceRequest(options);
  for (int f = 0; f < options.frames; ++f) {
    Camera camera;
    sequence.pose(f, camera);
    sequence.checkSameOccluders(ranks, f);
    ReferenceInfo info;
    request.run.label = "reference frame " + std::to_string(f);
    obtainReference(ranks, sequence.occlusion(), spec, options.render.settings, reference::ReferenceInput{}, request,
                    info);
  }
}

}  // namespace

CLI::App* addMotionCommand(CLI::App& app, MotionBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "motion", "an animated sequence per configuration against each frame's exact reference: error and flicker");
  options.render.scene = (std::filesystem::path(LGH_SOURCE_DIR) / "data" / "cornell_moving_light.gltf").string();
  options.render.settings.inputLights.vpls = 10000;
  options.render.settings.image.width = 160;
  options.render.settings.image.height = 90;
  addRenderBenchOptions(*command, options.render, kMotionOwnSettings);
  command->add_option("--frames", options.frames, "frames of the sequence")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  command->add_option("--fps", options.fps, "frames a second (the animation's time step)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--time", options.startTime,
                      "seconds into the animation of the first frame (default: its start)");
  command->add_option("--sun-step", options.sunStep, "every sun turns DAZIMUTH,DELEVATION degrees a frame");
  command->add_option("--point-step", options.pointStep, "every point light moves DX,DY,DZ a frame");
  command->add_option("--orbit-step", options.orbitStep, "the camera orbits the scene's centre DEG degrees a frame");
  command->add_option("--lightcut-samples", options.lightcutSamples, "the lightcuts' samples per pixel (0: none)")
      ->capture_default_str();
  command->add_option("--reference-pixels", options.referencePixels, "share of the pixels each frame's reference has")
      ->check(CLI::Range(1e-4, 1.0))
      ->capture_default_str();
  command->add_option("--reference-cache", options.referenceCache,
                      "reference cache folder (default: beside lgh-bench)");
  command->add_option("--csv", options.csvPath, "per frame and configuration: error, temporal error, ms");
  command->add_option("--images", options.imageDir,
                      "folder for each frame's reference | tested-history image (needs --reference-pixels 1)");
  return command;
}

int runMotionBench(const MotionBenchOptions& options) {
  // Rank 0 renders the sequence and measures it; with more ranks (mpiexec, srun) the others share each
  // frame's reference.
  const Ranks& ranks = Ranks::world();
  if (!ranks.root()) {
    shareTheReferences(options, ranks);
    return 0;
  }
  RenderBench bench(options.render);
  SceneGpu& gpu = bench.sceneGpu();
  SequenceScene sequence(bench.movingScene(), options, bench.scenePath());
  std::vector<Configuration> configs = configurations(options);
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (const Configuration& c : configs) renderers.push_back(std::make_unique<Renderer>(gpu, c.settings));
  std::vector<Series> series(configs.size());

  const SceneSpec spec{bench.scenePath(), options.render.settings.image.camera, bench.scenePath().stem().string()};
  ReferenceRequest request = referenceRequest(options);
  std::printf("lgh-bench motion: %s, %d frames at %g fps from %g s, %d x %d, %d VPLs (budget); %s; %s\n",
              spec.name.c_str(), options.frames, options.fps, sequence.time(0), options.render.settings.image.width,
              options.render.settings.image.height, options.render.settings.inputLights.vpls,
              bench.context().description().c_str(), ranksLine(ranks).c_str());
  std::ofstream csv;
  if (!options.csvPath.empty()) {
    const std::filesystem::path folder = std::filesystem::path(options.csvPath).parent_path();
    if (!folder.empty()) std::filesystem::create_directories(folder);
    csv.open(options.csvPath);
    if (!csv) throw std::runtime_error(options.csvPath + ": cannot write");
    csv << "frame,time,configuration,error,temporal_error,ms,bvh_build_ms,reference_pixels,"
           "temporal_irradiance_part,temporal_visibility_part\n";
  }
  if (!options.imageDir.empty()) std::filesystem::create_directories(options.imageDir);

  for (int f = 0; f < options.frames; ++f) {
    const double time = sequence.time(f);
    Camera camera;
    gpu.follow(sequence.pose(f, camera));
    sequence.checkSameOccluders(ranks, f);
    const CameraView view =
        makeCameraView(camera, options.render.settings.image.width, options.render.settings.image.height);
    std::vector<FrameStats> stats(configs.size());
    for (size_t c = 0; c < configs.size(); ++c) {
      if (configs[c].redrawVpls) {
        RenderSettings s = configs[c].settings;
        s.inputLights.seed = configs[c].settings.inputLights.seed + 1 + f;
        renderers[c]->setSettings(s);
      }
      stats[c] = renderers[c]->render(view);
      if (stats[c].nonFinitePixels > 0)
        throw std::runtime_error(configs[c].name + ": " + std::to_string(stats[c].nonFinitePixels) +
                                 " NaN/Inf pixels at frame " + std::to_string(f));
    }
    // The reference of this frame: the first configuration's G-buffer and S0 (every configuration but the
    // redrawn one draws the same S0 and sees the same surfaces).
    const Renderer& first = *renderers[0];
    const std::vector<gpu::GpuLight> lights =
        first.inputLights().lights.download<gpu::GpuLight>(first.inputLights().count);
    ReferenceInfo info;
    request.run.label = "reference frame " + std::to_string(f);
    const reference::ReferenceImage ref = obtainReference(ranks, sequence.occlusion(), spec, configs[0].settings,
                                                          referenceInput(first, fromGpuLights(lights)), request, info);
    std::vector<double> reference(ref.pixels.size()), unshadowed(ref.pixels.size());
    double norm = 0;
    for (size_t k = 0; k < ref.pixels.size(); ++k) {
      reference[k] = luminance(ref.shadowed[k]);
      unshadowed[k] = luminance(ref.unshadowed[k]);
      norm += reference[k] * reference[k];
    }
    norm = std::max(norm, 1e-300);
    // RMS of a frame-to-frame change over the pixels, relative to the reference's RMS.
    const auto temporal = [&](const std::vector<double>& now, const std::vector<double>& before) {
      double squared = 0;
      for (size_t k = 0; k < now.size(); ++k) squared += (now[k] - before[k]) * (now[k] - before[k]);
      return std::sqrt(squared / norm);
    };
    constexpr size_t kShown = 2;  // the tested history's images go to --images
    for (size_t c = 0; c < configs.size(); ++c) {
      const FrameImages images(*renderers[c]);
      const PixelValues values = valuesAtPixels(images, ref);
      std::vector<double> error(values.irradiance.size());
      double squared = 0;
      for (size_t k = 0; k < error.size(); ++k) {
        error[k] = values.shadowed(k) - reference[k];
        squared += error[k] * error[k];
      }
      const ErrorParts parts = errorParts(values.irradiance, values.visibility, unshadowed, reference);
      Series& s = series[c];
      s.error.push_back(std::sqrt(squared / norm));
      if (f > 0) {
        s.temporal.push_back(temporal(error, s.last));
        s.irradianceTemporal.push_back(temporal(parts.irradiance, s.lastParts.irradiance));
        s.visibilityTemporal.push_back(temporal(parts.visibility, s.lastParts.visibility));
      }
      s.ms.push_back(stats[c].totalMs() - stats[c].passMs(passes::kBvhBuild));
      s.last = error;
      s.lastParts = parts;
      if (csv)
        csv << f << ',' << time << ",\"" << configs[c].name << "\"," << s.error.back() << ','
            << (f > 0 ? std::to_string(s.temporal.back()) : "") << ',' << s.ms.back() << ','
            << stats[c].passMs(passes::kBvhBuild) << ',' << ref.pixels.size() << ','
            << (f > 0 ? std::to_string(s.irradianceTemporal.back()) : "") << ','
            << (f > 0 ? std::to_string(s.visibilityTemporal.back()) : "") << '\n';
      if (c == kShown && !options.imageDir.empty() && ref.full()) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.png", f);
        writeSideBySide(std::filesystem::path(options.imageDir) / name, ref, images,
                        options.render.settings.image.exposure);
      }
    }
    std::printf("  frame %3d  t %.3f s  reference %zu px (%s)  errors:", f, time, ref.pixels.size(),
                info.cached ? "cached" : "computed");
    for (const Series& s : series) std::printf(" %.3f", s.error.back());
    std::printf("\n");
    std::fflush(stdout);
  }

  TextTable table({"configuration", "mean error", "temporal error (RMS)", "temporal / no history", "irradiance's part",
                   "visibility's part", "ms a frame"});
  for (size_t c = 0; c < configs.size(); ++c) {
    const Series& s = series[c];
    // Against the same method's first configuration, its no-history one.
    size_t base = 0;
    while (configs[base].settings.indirectMethod != configs[c].settings.indirectMethod) ++base;
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.2f", rms(s.temporal) / rms(series[base].temporal));
    char e[32], t[32], irradiance[32] = "-", visibility[32] = "-";
    std::snprintf(e, sizeof e, "%.4f", mean(s.error));
    std::snprintf(t, sizeof t, "%.4f", rms(s.temporal));
    if (configs[c].settings.indirectMethod == IndirectMethod::Lgh) {  // the lightcuts' irradiance is shadowed
      std::snprintf(irradiance, sizeof irradiance, "%.4f", rms(s.irradianceTemporal));
      std::snprintf(visibility, sizeof visibility, "%.4f", rms(s.visibilityTemporal));
    }
    table.addRow({configs[c].name, e, t, ratio, irradiance, visibility, formatMs(mean(s.ms, 1))});
  }
  std::printf("over the sequence (errors relative to the reference's RMS; frame 0's time left out):\n");
  table.print(stdout);
  return 0;
}

}  // namespace lgh::bench
