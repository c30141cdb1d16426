// lgh-render: renders a glTF scene headless and writes the image.
//   lgh-render [SCENE] -o out.png|out.exr --width --height --camera --backend ...
#include <CLI/CLI.hpp>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "render/app/cli_settings.h"
#include "render/app/light_options.h"
#include "render/gl/context.h"
#include "render/renderer.h"
#include "render/scene/added_lights.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/scripted_motion.h"

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The project's default scene, found beside the source tree the binary was built from.
std::filesystem::path defaultScene() { return std::filesystem::path(LGH_DATA_DIR) / "cornell_box.gltf"; }

// What the command line asks for, besides the render settings.
struct Command {
  std::filesystem::path scenePath = defaultScene();
  std::filesystem::path output = "render.png";
  std::string backend = "auto";
  std::vector<std::string> aovOutputs;
  bool quiet = false, debugGL = false;
  int frames = 1;  // frames rendered from the same camera (same VPLs); the last one is written
  // An animated sequence: `sequence` frames (0: a still image) at `fps` from `time` (the animation's start
  // unless given), each written to the output pattern, the history carried from frame to frame.
  double time = 0.0, fps = 30.0;
  int sequence = 0;
  std::string sunStep, pointStep;
  double orbitStep = 0.0;
  lgh::RenderSettings settings;
  lgh::AddedLightOptions addedLights;
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// --help shows the options a first render needs; --help-all the rest (render/app/cli_settings.h).
void addOptions(CLI::App& app, Command& c, int argc, char** argv) {
  app.add_option("scene", c.scenePath, "glTF scene (.gltf or .glb)")->capture_default_str();
  app.add_option("-o,--output", c.output, "output image: .png/.jpg (tone-mapped sRGB) or .exr/.hdr (linear HDR)")
      ->capture_default_str();
  CLI::Option* frames =
      app.add_option("--frames", c.frames, "render N frames from the still camera and write the last (accumulated)")
          ->capture_default_str()
          ->check(CLI::Range(1, 1 << 20));
  app.add_option("--time", c.time, "seconds into the scene's animation (default: its start)");
  app.add_option("--sequence", c.sequence,
                 "render N frames of the animation from --time, each to -o (with %d: numbered)")
      ->check(CLI::Range(1, 1 << 20))
      ->excludes(frames);
  app.add_option("--fps", c.fps, "frames a second of --sequence")->capture_default_str()->check(CLI::PositiveNumber);
  const std::string advanced = lgh::addSettingsCommandLine(app, c.settings, argc, argv);
  app.add_option("--backend", c.backend, "OpenGL context: " + joined(lgh::gl::backendNames()))
      ->capture_default_str()
      ->group(advanced);
  app.add_option("--aov", c.aovOutputs, "also write an AOV: NAME=FILE, NAME one of " + joined(lgh::aovNames()))
      ->group(advanced);
  app.add_flag("-q,--quiet", c.quiet, "print nothing but errors")->group(advanced);
  app.add_flag("--debug-gl", c.debugGL, "KHR_debug context: GL errors abort the render with the driver's message")
      ->group(advanced);
  lgh::addLightOptions(app, c.addedLights, advanced);
  app.add_option("--sun-step", c.sunStep, "sequence: every sun turns DAZIMUTH,DELEVATION degrees a frame")
      ->group(advanced);
  app.add_option("--point-step", c.pointStep, "sequence: every point light moves DX,DY,DZ a frame")->group(advanced);
  app.add_option("--orbit-step", c.orbitStep, "sequence: the camera orbits the scene's centre DEG degrees a frame")
      ->group(advanced);
}

// Frame `frame`'s file: the output with its printf-style %d (e.g. frame_%04d.png) filled in, or, without
// one, with _NNNN before the extension.
std::filesystem::path sequencePath(const std::filesystem::path& output, int frame) {
  const std::string pattern = output.string();
  if (pattern.find('%') != std::string::npos) {
    std::vector<char> text(pattern.size() + 32);
    std::snprintf(text.data(), text.size(), pattern.c_str(), frame);
    return std::filesystem::path(text.data());
  }
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", frame);
  std::filesystem::path path = output;
  return path.replace_filename(output.stem().string() + number + output.extension().string());
}

// The output pattern may hold one integer conversion and nothing else printf would read.
void checkSequencePattern(const std::filesystem::path& output) {
  const std::string pattern = output.string();
  const size_t at = pattern.find('%');
  if (at == std::string::npos) return;
  size_t end = at + 1;
  while (end < pattern.size() && (std::isdigit(static_cast<unsigned char>(pattern[end])) != 0)) ++end;
  if (end >= pattern.size() || pattern[end] != 'd' || pattern.find('%', end) != std::string::npos)
    throw std::invalid_argument("--output " + pattern + ": a sequence's pattern takes one %d or %0Nd, nothing else");
}

// The --aov requests by AOV, checked (names, extensions, folders) before any work.
std::map<lgh::Aov, std::filesystem::path> checkedAovs(const Command& c) {
  std::map<lgh::Aov, std::filesystem::path> aovs;
  for (const std::string& spec : c.aovOutputs) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--aov expects NAME=FILE, got '" + spec + "'");
    aovs[lgh::parseAov(spec.substr(0, eq))] = spec.substr(eq + 1);
  }
  if (c.sequence > 0) checkSequencePattern(c.output);
  lgh::checkImagePath(c.sequence > 0 ? sequencePath(c.output, 0) : c.output);
  for (const auto& [aov, path] : aovs) lgh::checkImagePath(c.sequence > 0 ? sequencePath(path, 0) : path);
  return aovs;
}

void printLightPassSummary(const lgh::RenderSettings& settings, const lgh::LightStats& ls) {
  std::printf("S0         %zu input lights: %zu point lights, %zu emitter samples, %zu VPLs (%d bounces)\n",
              ls.inputLights, ls.pointLights, ls.emitterSamples, ls.vpls, settings.inputLights.bounces);
  std::string perLevel;
  for (size_t l = 0; l < ls.lightsPerLevel.size(); ++l)
    if (ls.lightsPerLevel[l] > 0) perLevel += " S" + std::to_string(l) + ":" + std::to_string(ls.lightsPerLevel[l]);
  const lgh::LightPassSettings& pass = settings.lightPass;
  if (pass.bruteForce)
    std::printf("light pass brute force over S0 (%zu lights at every pixel)\n", ls.inputLights);
  else
    std::printf("LGH        L = %d, alpha %.3g, start level %d, interleave %dx%d, drawn%s\n", ls.levels,
                double(pass.alpha), pass.startLevel, pass.interleave, pass.interleave, perLevel.c_str());
  if (settings.shadows.samples > 0)
    std::printf("shadows    k = %d per pixel, %s estimator, filter %d passes\n", settings.shadows.samples,
                settings.shadows.estimator.c_str(), settings.filter.passes);
  if (pass.overdraw)
    std::printf("overdraw   %.1f fragments rasterized per pixel (max %u), %.1f shaded, efficiency %.2f (%s volumes)\n",
                ls.rasterizedPerPixel, ls.maxRasterized, ls.shadedPerPixel, ls.efficiency(),
                pass.volumeCulling ? "culled" : "cube");
}

void printSummary(const Command& c, const lgh::gl::Context& context, const lgh::SceneGpu& sceneGpu,
                  const lgh::Camera& camera, const lgh::FrameStats& stats, double loadMs, double setupMs) {
  const lgh::Scene& scene = sceneGpu.scene();
  std::printf("scene      %s\n", c.scenePath.string().c_str());
  std::printf("context    %s\n", context.description().c_str());
  std::printf("image      %d x %d -> %s\n", c.settings.image.width, c.settings.image.height, c.output.string().c_str());
  std::printf("camera     %s\n", camera.name.empty() ? "(framing the scene bounds)" : camera.name.c_str());
  std::printf("triangles  %zu (BVH: %zu nodes, depth %d, built in %.1f ms)\n", scene.triangleCount(),
              sceneGpu.bvh().stats.nodeCount, sceneGpu.bvh().stats.maxDepth, sceneGpu.bvhBuildMs());
  std::printf("lights     %zu punctual, %zu emissive materials\n", scene.lights.size(),
              size_t(std::count_if(scene.materials.begin(), scene.materials.end(),
                                   [](const lgh::Material& m) { return m.isEmissive(); })));
  if (c.settings.indirect()) printLightPassSummary(c.settings, stats.lights);
  if (c.settings.indirect() && c.settings.accumulation.enabled)
    std::printf("accumulate %d frames in the history (at most %d)\n", stats.accumulatedFrames,
                c.settings.accumulation.maxFrames);
  std::printf("load       %.1f ms, GPU setup %.1f ms\n", loadMs, setupMs);
  std::printf("passes     (wall ms, glFinish-bracketed)\n");
  for (const auto& p : stats.passes) std::printf("  %-18s %9.2f\n", p.name.c_str(), p.wallMs);
  std::printf("  %-18s %9.2f\n", "total", stats.totalMs());
  const lgh::gl::MemoryRegistry& memory = lgh::gl::memory();
  std::printf("GPU memory (buffers and textures by owner, after the last frame)\n");
  for (const auto& o : memory.byOwner())
    std::printf("  %-18s %10s  %3zu %s\n", o.owner.c_str(), lgh::gl::formatBytes(double(o.bytes)).c_str(), o.objects,
                o.objects == 1 ? "object" : "objects");
  std::printf("  %-18s %10s, peak %s\n", "total", lgh::gl::formatBytes(double(memory.liveBytes())).c_str(),
              lgh::gl::formatBytes(double(memory.peakBytes())).c_str());
}

int run(int argc, char** argv) {
  CLI::App app{"lgh-render: global illumination with a lighting grid hierarchy, rendered headless"};
  Command c;
  addOptions(app, c, argc, argv);
  CLI11_PARSE(app, argc, argv);
  // More than one frame is asked for to accumulate them, unless --accumulate says otherwise.
  if (c.frames > 1 && app.count("--accumulate") == 0) c.settings.accumulation.enabled = true;
  const lgh::RenderSettings& settings = c.settings;
  // Everything cheap is validated before any work: a bad AOV name or extension fails in milliseconds.
  const std::map<lgh::Aov, std::filesystem::path> aovs = checkedAovs(c);
  const lgh::ToneMap toneMap = lgh::parseToneMap(settings.image.toneMap);

  const auto t0 = Clock::now();
  lgh::Scene scene = lgh::loadScene(c.scenePath);
  lgh::addCommandLineLights(scene, c.addedLights.suns, c.addedLights.points);
  const double loadMs = msSince(t0);
  for (const std::string& w : scene.warnings) std::cerr << "lgh-render: warning: " << w << "\n";
  if (!lgh::sceneHasLight(scene)) std::cerr << "lgh-render: note: " << lgh::noLightHint() << "\n";
  const lgh::ScriptedMotion motion = lgh::parseScriptedMotion(c.sunStep, c.pointStep, c.orbitStep);
  const double startTime = app.count("--time") > 0 ? c.time : scene.animation.start;
  if (!std::isfinite(startTime)) throw std::invalid_argument("--time must be a finite number of seconds");
  const std::vector<lgh::PunctualLight> startLights = scene.lights;
  lgh::poseScene(scene, startTime);
  lgh::Camera camera = lgh::resolveCamera(scene, settings);

  lgh::gl::ContextOptions contextOptions;
  contextOptions.backend = lgh::gl::parseBackend(c.backend);
  contextOptions.debug = c.debugGL;
  const auto context = lgh::gl::Context::create(contextOptions);

  const auto t1 = Clock::now();
  lgh::gl::memory().setLimit(size_t(double(settings.gpuMemoryLimit) * 1e6));  // the scene counts too
  lgh::SceneGpu sceneGpu(scene, settings.bvhLayout);
  lgh::Renderer renderer(sceneGpu, settings);
  const double setupMs = msSince(t1);
  const auto write = [&](int frame) {
    const auto file = [&](const std::filesystem::path& path) {
      return c.sequence > 0 ? sequencePath(path, frame) : path;
    };
    lgh::writeImage(file(c.output), renderer.readImage(lgh::Aov::Final), settings.image.exposure, toneMap);
    for (const auto& [aov, path] : aovs) {
      if (lgh::isDataAov(aov))
        lgh::writeImage(file(path), renderer.readImage(aov), 0.0f, lgh::ToneMap::Clamp);
      else
        lgh::writeImage(file(path), renderer.readImage(aov), settings.image.exposure, toneMap);
    }
  };
  lgh::FrameStats stats;
  if (c.sequence == 0) {
    const lgh::CameraView view = lgh::makeCameraView(camera, settings.image.width, settings.image.height);
    for (int f = 0; f < c.frames; ++f) stats = renderer.render(view);
    write(0);
  }
  // A sequence: each frame posed at its time, the scripted motions moved on, one render, the history carried.
  for (int f = 0; f < c.sequence; ++f) {
    const double time = startTime + double(f) / c.fps;
    lgh::PoseChange change = lgh::poseScene(scene, time);
    camera = lgh::resolveCamera(scene, settings);
    change.merge(lgh::applyScriptedMotion(motion, f, startLights, scene, camera));
    sceneGpu.follow(change);
    stats = renderer.render(lgh::makeCameraView(camera, settings.image.width, settings.image.height));
    write(f);
    if (!c.quiet)
      std::printf("frame %4d  t %8.4f s  %9.2f ms (BVH build %.2f ms)  -> %s\n", f, time, stats.totalMs(),
                  stats.passMs(lgh::passes::kBvhBuild), sequencePath(c.output, f).string().c_str());
  }
  if (!c.quiet) printSummary(c, *context, sceneGpu, camera, stats, loadMs, setupMs);
  if (stats.nonFinitePixels > 0)
    std::cerr << "lgh-render: warning: " << stats.nonFinitePixels << " pixels were NaN or Inf and were written black\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "lgh-render: error: " << e.what() << "\n";
    return 1;
  }
}
