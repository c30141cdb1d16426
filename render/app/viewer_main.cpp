// lgh-viewer: the interactive GI viewer. A window shows frames of the same renderer as lgh-render,
// with the same settings under the same names, and a panel to change them.
//   lgh-viewer [SCENE] [--width W --height H (the window) --camera NAME ... every lgh-render setting]
//              [--view AOV] [--points L] [--render-scale S] [--script "frames=3;set alpha=2;..."]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "render/app/cli_settings.h"
#include "render/app/light_options.h"
#include "render/app/viewer_app.h"
#include "render/gl/context.h"
#include "render/scene/added_lights.h"

namespace {

std::filesystem::path defaultScene() { return std::filesystem::path(LGH_DATA_DIR) / "cornell_box.gltf"; }

int run(int argc, char** argv) {
  CLI::App app{"lgh-viewer: interactive global illumination with a lighting grid hierarchy (needs a display)"};
  std::filesystem::path scenePath = defaultScene();
  std::string view = "final", script;
  lgh::ViewerState state;
  lgh::ViewerOptions options;
  bool debugGL = false;
  lgh::AddedLightOptions addedLights;

  app.add_option("scene", scenePath, "glTF scene (.gltf or .glb)")->capture_default_str();
  app.add_option(
         "--view", view,
         "image shown: " +
             [] {
               std::string s;
               for (const auto& n : lgh::aovNames()) s += (s.empty() ? "" : ", ") + n;
               return s;
             }())
      ->capture_default_str();
  app.add_option("--points", state.pointsLevel, "draw the grid lights of level L as points (0: none)")
      ->check(CLI::Range(0, 11))
      ->capture_default_str();
  app.add_option("--render-scale", state.renderScale,
                 "image pixels per window pixel (0.25-1; lower is faster); without --width/--height the window is "
                 "1280 x 720 at scale 0.5")
      ->check(CLI::Range(0.25f, 1.0f))
      ->capture_default_str();
  app.add_option("--script", script,
                 "play commands, ';'-separated: frames=N, set NAME=VALUE, view=AOV, points=L, "
                 "light=I position|direction|intensity=X,Y,Z, screenshot=FILE (.png: the image shown; .exr: linear), "
                 "window-screenshot=FILE (panel included), window=WxH (resize), quit. "
                 "The image is then --width x --height (default 640 x 360), whatever the window's size");
  app.add_option("--screenshot-prefix", options.screenshotPrefix, "screenshot key (F12, P): PREFIX-NNN.png and .exr")
      ->capture_default_str();
  app.add_flag("-q,--quiet", options.quiet, "print nothing but errors");
  app.add_flag("--debug-gl", debugGL, "KHR_debug context: GL errors abort with the driver's message");
  // The viewer accumulates while the view is still (--accumulate=false: every frame on its own).
  state.settings.accumulation.enabled = true;
  const std::string advanced = lgh::addSettingsCommandLine(app, state.settings, argc, argv);
  lgh::addLightOptions(app, addedLights, advanced);
  CLI11_PARSE(app, argc, argv);
  // Without a size the window opens at 1280 x 720 and renders at half that (lgh-render's default
  // 640 x 360): room for the panel, and frames as fast as lgh-render's.
  const bool sized = app.count("--width") > 0 || app.count("--height") > 0;
  const int windowWidth = sized ? state.settings.image.width : 1280,
            windowHeight = sized ? state.settings.image.height : 720;
  if (!sized && app.count("--render-scale") == 0) state.renderScale = 0.5f;

  // Everything cheap is checked before the window opens: a typo costs milliseconds.
  state.view = lgh::parseAov(view);
  if (state.view == lgh::Aov::Overdraw) state.settings.lightPass.overdraw = true;
  lgh::parseToneMap(state.settings.image.toneMap);
  const std::vector<lgh::ScriptCommand> commands = lgh::parseScript(script);
  lgh::Scene scene = lgh::loadScene(scenePath);
  lgh::addCommandLineLights(scene, addedLights.suns, addedLights.points);  // editable in the light panel
  for (const std::string& w : scene.warnings) std::cerr << "lgh-viewer: warning: " << w << "\n";
  if (!lgh::sceneHasLight(scene)) std::cerr << "lgh-viewer: note: " << lgh::noLightHint() << "\n";
  lgh::resolveCamera(scene, state.settings);  // an unknown --camera fails here, listing the cameras
  state.time = scene.animation.start;
  lgh::poseScene(scene, state.time);
  for (const lgh::ScriptCommand& c : commands)
    if (c.kind == lgh::ScriptCommand::Kind::Light && size_t(c.number) >= scene.lights.size())
      throw std::invalid_argument("script: '" + c.text + "': " + scenePath.filename().string() + " has " +
                                  std::to_string(scene.lights.size()) + " punctual lights");

  lgh::gl::ContextOptions contextOptions;
  contextOptions.backend = lgh::gl::Backend::Window;
  contextOptions.debug = debugGL;
  contextOptions.windowWidth = windowWidth;
  contextOptions.windowHeight = windowHeight;
  contextOptions.windowTitle = "lgh-viewer - " + scenePath.filename().string();
  std::unique_ptr<lgh::gl::Context> context;
  try {
    context = lgh::gl::Context::create(contextOptions);
  } catch (const lgh::gl::ContextError& e) {
    throw lgh::gl::ContextError(std::string(e.what()) +
                                "\nlgh-viewer needs a display with OpenGL 4.5 core: run it on a desktop, over X "
                                "forwarding, or under `xvfb-run -a` (a virtual display); without one, lgh-render "
                                "renders the same frames (its --backend option picks the headless context)");
  }
  if (!options.quiet) std::printf("context    %s\n", context->description().c_str());

  lgh::Viewer viewer(scene, *context, state, options);
  viewer.run(commands);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "lgh-viewer: error: " << e.what() << "\n";
    return 1;
  }
}
