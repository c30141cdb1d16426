#pragma once
// The interactive viewer: a GLFW window showing frames of lgh::Renderer (the same passes and
// settings as lgh-render), a Dear ImGui panel, orbit/fly navigation, light editing and screenshots.
// Frames are rendered when something that changes the image changes (camera, settings, lights,
// window size), not continuously: on a software rasterizer a frame takes seconds and the panel must
// stay responsive. Exposure, tone curve, view and overlays only redo the cheap display pass.

#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "render/app/display_pass.h"
#include "render/app/grid_points_pass.h"
#include "render/app/viewer_camera.h"
#include "render/app/viewer_panel.h"
#include "render/app/viewer_script.h"
#include "render/gl/context.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh {

struct ViewerOptions {
  std::string screenshotPrefix = "lgh-viewer";  // interactive screenshots: PREFIX-NNN.png and .exr
  bool quiet = false;
};

class Viewer {
 public:
  // The context must be the window backend's and current; it must outlive the viewer.
  // An animated scene is posed (poseScene) at the panel's time: `scene` is the one the viewer moves.
  Viewer(Scene& scene, gl::Context& context, const ViewerState& initial, const ViewerOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Plays `script` (if any), then runs interactively until the window closes or the script quits.
  // Errors while scripted are thrown; interactive ones are shown in the panel.
  void run(const std::vector<ScriptCommand>& script);

  // Called by the GLFW callbacks (chained behind ImGui's).
  void onScroll(double steps);
  void onKeyPressed(int key);

 private:
  void step(bool forceRender);  // one frame of the window: input, panel, render, display
  bool needsRender() const;     // the last frame is out of date (or continuous rendering)
  bool minimized() const;
  bool runCommand(const ScriptCommand& c);  // false: quit
  void handleInput(PanelRequests& requests);
  void applyLightChanges(const std::vector<size_t>& changed);
  // The animation at state_.time (advanced by `dt` while playing, looping): moved meshes and lights follow.
  void playAnimation(double dt);
  void resetCamera();
  RenderSettings frameSettings() const;  // the settings a frame renders with (size, overdraw)
  std::string frameKey() const;          // what a rendered frame depends on, to detect changes
  void render();
  void display();
  void present();
  void writeScreenshot(const std::filesystem::path& path);
  void captureWindow(const std::filesystem::path& path);  // the back buffer, before it is shown
  std::filesystem::path nextScreenshotPath(const char* extension) const;

  Scene& sceneData_;
  gl::Context& context_;
  GLFWwindow* window_;
  ViewerOptions options_;
  ViewerState state_;
  SceneGpu scene_;
  Renderer renderer_;
  DisplayPass displayPass_;
  GridPointsPass gridPointsPass_;
  DisplayImage displayImage_;
  CameraController camera_;
  std::string cameraSetting_;  // settings.image.camera the controller was last reset to
  CameraView frameView_;       // of the last rendered frame
  FrameStats lastFrame_;
  TimingHistory timings_;
  bool rendered_ = false;
  std::string renderedKey_;              // frameKey() of the last frame (or of the last failed attempt)
  std::string message_;                  // shown in the panel
  std::filesystem::path windowCapture_;  // write the next presented window here (script)
  bool fixedSize_ = false;               // scripted: render at settings.image.width x height, not the window's size
  bool showPanel_ = true;
  bool scripted_ = false;
  double lastTime_ = 0;
  double lastAnimationTime_ = 0;
  double posedTime_ = std::numeric_limits<double>::quiet_NaN();  // state_.time the scene was last posed at
  glm::dvec2 lastCursor_{0.0};
  double scrollSteps_ = 0;
  std::vector<int> keysPressed_;
};

}  // namespace lgh
