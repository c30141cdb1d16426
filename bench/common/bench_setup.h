#pragma once
// What every benchmark sets up the same way: the OpenGL context (--backend), the render settings from
// the command line (render/settings.h through visitSettings, so --width, --vpls, --alpha ... have one
// name, range and help everywhere), the scene on the GPU and a Renderer with its camera, and the few
// frame-level helpers the benchmarks share (the VPL target, the light pass's and shadows' times).

#include <CLI/CLI.hpp>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/camera_view.h"
#include "render/gl/context.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "render/scene/scene_gpu.h"
#include "render/settings.h"

namespace lgh::bench {

// --backend NAME: the OpenGL context (checked against gl::backendNames() while parsing).
void addBackendOption(CLI::App& command, std::string& backend);
std::unique_ptr<gl::Context> createContext(const std::string& backend);

// --NAME for every render setting (render/settings.h), defaults from `settings`, except the bench's
// own: settings it sets per measurement, or sweeps as a list it declares itself under the same name.
void addRenderSettingsOptions(CLI::App& command, RenderSettings& settings, const std::vector<std::string>& own);

// A Renderer and the camera it draws from (the settings' camera in the scene, at the settings' size).
class BenchRenderer {
 public:
  BenchRenderer(const SceneGpu& scene, const RenderSettings& settings);

  Renderer& renderer() { return renderer_; }
  const CameraView& view() const { return view_; }
  // One frame with `settings` (S0 and the hierarchy are rebuilt when their settings changed), not
  // accumulated with earlier ones.
  FrameStats render(const RenderSettings& settings);
  // Renders with the VPL budget settings.inputLights.vpls raised until the VPLs made meet `target`
  // within 2% (light paths that leave the scene deposit nothing); leaves that budget in `settings`.
  FrameStats renderToVplTarget(RenderSettings& settings, size_t target);

 private:
  CameraView view_;
  Renderer renderer_;
};

// The options of a benchmark that renders one scene (lgh-bench light, frame).
struct RenderBenchOptions {
  std::string scene;        // empty: ../shared/scenes/sponza_sun if present, else the project's Cornell box
  RenderSettings settings;  // a bench sets its own defaults here before addRenderBenchOptions
  std::string backend = "auto";
};
// --scene, the render settings but `own` (addRenderSettingsOptions) and --backend.
void addRenderBenchOptions(CLI::App& command, RenderBenchOptions& options, const std::vector<std::string>& own);

// The scene chosen by the options, loaded, the context, the scene on the GPU and a renderer, in that
// order (a missing scene fails before the context is made).
class RenderBench {
 public:
  explicit RenderBench(const RenderBenchOptions& options);

  const std::filesystem::path& scenePath() const { return path_; }
  const std::string& sceneReason() const { return why_; }  // why this scene, for the output
  const Scene& scene() const { return scene_; }
  // For a bench that moves the scene (poseScene) and has the GPU follow it (SceneGpu::follow).
  Scene& movingScene() { return scene_; }
  SceneGpu& sceneGpu() { return *gpu_; }
  const gl::Context& context() const { return *context_; }
  BenchRenderer& renderer() { return *renderer_; }

 private:
  std::string why_;
  std::filesystem::path path_;
  Scene scene_;
  std::unique_ptr<gl::Context> context_;
  std::unique_ptr<SceneGpu> gpu_;
  std::unique_ptr<BenchRenderer> renderer_;
};

// `path` as results files record it: relative to the source tree (a reference scene reads
// ../shared/scenes/...), so that committed CSV/JSON name no machine's folders.
std::string sourceRelative(const std::filesystem::path& path);

// Grid lights the light pass drew: every level but S0.
size_t gridLightsOf(const LightStats& lights);
// The light pass as a frame pays for it: interleave split + light pass + interleave resolve (ms).
double lightPassMs(const FrameStats& stats);
// The indirect shadows: shadow targets + shadow rays + shadow filter (ms).
double shadowMs(const FrameStats& stats);
// The stochastic lightcuts' frame without its tree build: cuts, sampling, irradiance filter.
double lightcutsMs(const FrameStats& stats);
// The indirect method's passes, whichever ran: the LGH's (lightPassMs + shadowMs) or the lightcuts'.
double indirectMs(const FrameStats& stats);

}  // namespace lgh::bench
