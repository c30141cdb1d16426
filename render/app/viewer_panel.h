#pragma once
// The viewer's Dear ImGui panel. The render settings are drawn by walking visitSettings (one widget
// per setting, its range from SettingInfo, its help as the tooltip), so the panel shows every
// parameter of lgh-render under the same name; the rest is the viewer's own: what to show, the
// camera, the scene's lights and the per-pass timings of recent frames.

#include <deque>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "render/scene/scene.h"

namespace lgh {

// Everything the panel edits.
struct ViewerState {
  RenderSettings settings;            // width and height follow the window (times renderScale)
  Aov view = Aov::Final;              // the image shown
  int pointsLevel = 0;                // grid lights of this level drawn as points over it; 0: none
  float pointSize = 6.0f;             // pixels of the image
  float renderScale = 1.0f;           // image pixels per window pixel (below 1: faster frames)
  bool continuous = false;            // render every frame, not only after a change
  bool fly = false;                   // camera: fly (look around in place) rather than orbit
  std::vector<PunctualLight> lights;  // the scene's punctual lights as edited
  int selectedLight = 0;
  double time = 0.0;     // seconds into the scene's animation (when it has one)
  bool playing = false;  // the animation advances in real time (looping)
};

// What the panel asks the viewer to do this frame.
struct PanelRequests {
  std::vector<size_t> changedLights;  // indices into ViewerState::lights
  bool resetCamera = false;           // back to the selected scene camera
  bool screenshot = false;
};

// Per-pass times of the last frames, for the live graphs.
class TimingHistory {
 public:
  static constexpr size_t kFrames = 120;
  void add(const FrameStats& stats);
  void draw() const;

 private:
  struct Series {
    std::string name;
    std::deque<float> ms;
  };
  std::vector<Series> passes_;  // in the order passes first ran
  std::deque<float> total_;
};

// Facts the panel shows but does not edit.
struct PanelInfo {
  const Scene* scene = nullptr;
  std::string context;  // the GL context's description
  int imageWidth = 0, imageHeight = 0;
  const FrameStats* lastFrame = nullptr;  // null before the first frame
  const TimingHistory* timings = nullptr;
  std::string message;     // the last screenshot written, or the last error
  bool fixedSize = false;  // scripted: the image size is the settings', not the window's
};

PanelRequests drawPanel(ViewerState& state, const PanelInfo& info);

}  // namespace lgh
