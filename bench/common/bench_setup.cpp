#include "bench/common/bench_setup.h"

#include <algorithm>

#include "bench/common/light_source.h"
#include "render/app/cli_settings.h"

namespace lgh::bench {

void addBackendOption(CLI::App& command, std::string& backend) {
  std::string names;
  for (const std::string& name : gl::backendNames()) names += (names.empty() ? "" : ", ") + name;
  command.add_option("--backend", backend, "OpenGL context: " + names)
      ->check(CLI::IsMember(gl::backendNames()))
      ->capture_default_str();
}

std::unique_ptr<gl::Context> createContext(const std::string& backend) {
  gl::ContextOptions options;
  options.backend = gl::parseBackend(backend);
  return gl::Context::create(options);
}

void addRenderSettingsOptions(CLI::App& command, RenderSettings& settings, const std::vector<std::string>& own) {
  addSettingsOptions(command, settings, "Render settings");
  for (const std::string& name : own) {
    CLI::Option* option = command.get_option_no_throw("--" + name);
    if (!option) throw std::logic_error("addRenderSettingsOptions: no render setting '" + name + "'");
    command.remove_option(option);
  }
}

BenchRenderer::BenchRenderer(const SceneGpu& scene, const RenderSettings& settings)
    : view_(makeCameraView(resolveCamera(scene.scene(), settings), settings.image.width, settings.image.height)),
      renderer_(scene, settings) {}

FrameStats BenchRenderer::render(const RenderSettings& settings) {
  renderer_.setSettings(settings);
  renderer_.restartAccumulation();  // one frame, never averaged with the previous call's
  return renderer_.render(view_);
}

FrameStats BenchRenderer::renderToVplTarget(RenderSettings& settings, size_t target) {
  constexpr int kMaxRaises = 4;
  constexpr double kMaxBudget = 16e6;  // the vpls setting's range
  settings.inputLights.vpls = int(target);
  FrameStats stats = render(settings);
  for (int attempt = 0; attempt < kMaxRaises && stats.lights.vpls > 0 && stats.lights.vpls * 100 < target * 98;
       ++attempt) {
    const double raised = double(settings.inputLights.vpls) * double(target) / double(stats.lights.vpls) * 1.005;
    settings.inputLights.vpls = int(std::min(raised, kMaxBudget));
    stats = render(settings);
  }
  return stats;
}

void addRenderBenchOptions(CLI::App& command, RenderBenchOptions& options, const std::vector<std::string>& own) {
  command
      .add_option("--scene", options.scene, "glTF scene (default: ../shared/scenes/sponza_sun, else data/cornell_box)")
      ->check(CLI::ExistingFile);
  addRenderSettingsOptions(command, options.settings, own);
  addBackendOption(command, options.backend);
}

RenderBench::RenderBench(const RenderBenchOptions& options)
    : path_(chooseRenderScene(options.scene, why_)),
      scene_(loadScene(path_)),
      context_(createContext(options.backend)),
      gpu_(std::make_unique<SceneGpu>(scene_, options.settings.bvhLayout)),
      renderer_(std::make_unique<BenchRenderer>(*gpu_, options.settings)) {}

std::string sourceRelative(const std::filesystem::path& path) {
  const std::filesystem::path source = std::filesystem::weakly_canonical(LGH_SOURCE_DIR);
  const std::filesystem::path relative = std::filesystem::weakly_canonical(path).lexically_relative(source);
  return relative.empty() ? path.string() : relative.string();
}

size_t gridLightsOf(const LightStats& lights) {
  size_t n = 0;
  for (size_t l = 1; l < lights.lightsPerLevel.size(); ++l) n += lights.lightsPerLevel[l];
  return n;
}

double lightPassMs(const FrameStats& stats) {
  return stats.passMs(passes::kInterleaveSplit) + stats.passMs(passes::kLightPass) +
         stats.passMs(passes::kInterleaveResolve);
}

double shadowMs(const FrameStats& stats) {
  return stats.passMs(passes::kShadowTargets) + stats.passMs(passes::kShadowRays) + stats.passMs(passes::kShadowFilter);
}

double lightcutsMs(const FrameStats& stats) {
  return stats.passMs(passes::kLightcutCuts) + stats.passMs(passes::kLightcutSampling) +
         stats.passMs(passes::kIrradianceFilter);
}

double indirectMs(const FrameStats& stats) { return lightPassMs(stats) + shadowMs(stats) + lightcutsMs(stats); }

}  // namespace lgh::bench
