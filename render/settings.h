#pragma once
// Every render parameter, declared once: name, default, range and help. The CLI (lgh-render), the
// viewer's UI and the sweep's CSV/JSON all walk this list with visitSettings(), so a parameter
// added here appears everywhere with the same name and limits.

#include <string>

namespace lgh {

struct RenderSettings {
  int width = 640;
  int height = 360;
  std::string camera;        // scene camera name; empty: the scene's first camera, or frame its bounds
  float exposure = 0.0f;     // EV applied before tone mapping (display formats only)
  std::string toneMap = "aces";
  bool directShadows = true;
  float clampDistance = 0.0f;  // d_c in metres; 0 = automatic (1e-3 of the scene diagonal)
};

struct SettingInfo {
  const char* name;  // also the CLI flag: --name
  const char* help;
  double min = 0, max = 0;  // inclusive range for numbers; min == max means unbounded
};

// visit(value&, SettingInfo) for each setting, in the order users see them.
template <typename Settings, typename Visitor>
void visitSettings(Settings& s, Visitor&& visit) {
  visit(s.width, SettingInfo{"width", "image width in pixels", 1, 16384});
  visit(s.height, SettingInfo{"height", "image height in pixels", 1, 16384});
  visit(s.camera, SettingInfo{"camera", "scene camera by name (default: the scene's first camera, else one framing the scene's bounds)"});
  visit(s.exposure, SettingInfo{"exposure", "exposure in EV for PNG/JPEG output", -20, 20});
  visit(s.toneMap, SettingInfo{"tonemap", "tone curve for PNG/JPEG output: clamp, reinhard, aces"});
  visit(s.directShadows, SettingInfo{"direct-shadows", "trace shadow rays for direct light"});
  visit(s.clampDistance, SettingInfo{"clamp-distance", "d_c: distances below it count as d_c in 1/d^2 (0 = 1e-3 x scene diagonal)", 0, 1e9});
}

}  // namespace lgh
