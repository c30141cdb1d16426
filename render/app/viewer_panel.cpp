#include "render/app/viewer_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <type_traits>

#include "render/gl/memory.h"
#include "render/scene/added_lights.h"

namespace lgh {
namespace {

void tooltip(const char* help) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", help);
}

bool cameraCombo(const char* label, std::string& value, const Scene& scene) {
  const std::string preview = !value.empty()          ? value
                              : scene.cameras.empty() ? std::string("(framing the scene)")
                                                      : scene.cameras.front().name + " (first)";
  bool changed = false;
  if (ImGui::BeginCombo(label, preview.c_str())) {
    for (const Camera& c : scene.cameras)
      if (ImGui::Selectable(c.name.c_str(), c.name == value)) {
        value = c.name;
        changed = true;
      }
    if (scene.cameras.empty()) ImGui::TextDisabled("the scene has no cameras");
    ImGui::EndCombo();
  }
  return changed;
}

// A combo over SettingInfo::choices.
bool choiceCombo(const char* label, std::string& value, const char* choices) {
  bool changed = false;
  if (ImGui::BeginCombo(label, value.c_str())) {
    for (const std::string& choice : choiceList(choices))
      if (ImGui::Selectable(choice.c_str(), value == choice)) {
        value = choice;
        changed = true;
      }
    ImGui::EndCombo();
  }
  return changed;
}

// One widget per render setting of `tier`, chosen by its type and range: sliders within SettingInfo's
// limits (logarithmic where the range spans orders of magnitude), checkboxes for flags, combos for choices.
bool drawSettings(RenderSettings& settings, const Scene& scene, SettingTier tier) {
  bool changed = false;
  visitSettings(settings, [&](auto& value, const SettingInfo& info) {
    using T = std::decay_t<decltype(value)>;
    const std::string name = info.name;
    if (info.tier != tier) return;
    if (name == "width" || name == "height") return;  // the window decides (shown above)
    constexpr ImGuiSliderFlags kClamp = ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_NoRoundToFormat;
    const bool bounded = info.min < info.max;
    if constexpr (std::is_same_v<T, bool>) {
      changed |= ImGui::Checkbox(info.name, &value);
    } else if constexpr (std::is_same_v<T, int>) {
      if (bounded && info.max - info.min <= 100) {
        changed |= ImGui::SliderInt(info.name, &value, int(info.min), int(info.max), "%d", kClamp);
      } else if (bounded && info.max <= double(INT_MAX / 2)) {  // ImGui's slider limit
        changed |= ImGui::SliderInt(info.name, &value, int(info.min), int(info.max), "%d",
                                    kClamp | ImGuiSliderFlags_Logarithmic);
      } else if (ImGui::InputInt(info.name, &value)) {
        if (bounded) value = int(std::clamp(double(value), info.min, info.max));
        changed = true;
      }
    } else if constexpr (std::is_same_v<T, float>) {
      float lo = float(info.min), hi = float(info.max);
      const char* format = "%.3g";
      bool logarithmic = hi - lo > 100.0f || (lo > 0.0f && hi / lo > 50.0f);
      if (name == "clamp-distance") {  // up to the scene's size, not the 1e9 the CLI accepts
        hi = std::max(scene.bounds.diagonal(), 1e-3f);
        format = value > 0.0f ? "%.3g m" : "auto";
      }
      if (bounded)
        changed |= ImGui::SliderFloat(info.name, &value, lo, hi, format,
                                      kClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0));
      else
        changed |= ImGui::InputFloat(info.name, &value);
    } else if constexpr (std::is_enum_v<T>) {
      std::string text = choiceName(value, info.choices);
      if (choiceCombo(info.name, text, info.choices)) {
        value = choiceValue<T>(text, info.choices);
        changed = true;
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (name == "camera")
        changed |= cameraCombo(info.name, value, scene);
      else if (info.choices)
        changed |= choiceCombo(info.name, value, info.choices);
      else
        ImGui::LabelText(info.name, "%s", value.c_str());
    }
    tooltip(info.help);
  });
  return changed;
}

// Edits the selected punctual light: position, direction (as azimuth and elevation; for the sun, of
// where it stands in the sky) and intensity (colour x strength). Returns true if it changed.
bool drawLight(PunctualLight& light, float sceneSize) {
  bool changed = false;
  const bool directional = light.type == LightType::Directional;
  if (light.type != LightType::Directional)
    changed |= ImGui::DragFloat3("position", &light.position.x, 0.002f * sceneSize, 0.0f, 0.0f, "%.3f");
  if (light.type != LightType::Point) {
    // The same angles as lgh-render --sun AZIMUTH,ELEVATION (render/scene/added_lights.h).
    const glm::vec2 angles = sunAngles(directional ? -light.direction : light.direction);
    float azimuth = angles.x, elevation = angles.y;
    bool turned = ImGui::SliderFloat(directional ? "sun azimuth" : "azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
    turned |= ImGui::SliderFloat(directional ? "sun elevation" : "elevation", &elevation, -90.0f, 90.0f, "%.1f deg");
    if (turned) {
      const glm::vec3 dir = sunDirection(azimuth, elevation);
      light.direction = directional ? -dir : dir;
      changed = true;
    }
  }
  float strength = std::max(light.intensity.r, std::max(light.intensity.g, light.intensity.b));
  glm::vec3 colour = strength > 0.0f ? light.intensity / strength : glm::vec3(1.0f);
  bool recoloured = ImGui::ColorEdit3("colour", &colour.x, ImGuiColorEditFlags_Float);
  recoloured |= ImGui::DragFloat("strength", &strength, 0.01f * std::max(strength, 0.1f), 0.0f, 1e9f,
                                 directional ? "%.3g lux" : "%.3g cd", ImGuiSliderFlags_AlwaysClamp);
  if (recoloured) {
    light.intensity = colour * strength;
    changed = true;
  }
  return changed;
}

const char* lightTypeName(LightType type) {
  return type == LightType::Point ? "point" : type == LightType::Spot ? "spot" : "directional";
}

}  // namespace

void TimingHistory::add(const FrameStats& stats) {
  for (Series& s : passes_) s.ms.push_back(0.0f);  // a pass that did not run this frame took 0
  for (const gl::PassTiming& p : stats.passes) {
    auto it = std::find_if(passes_.begin(), passes_.end(), [&](const Series& s) { return s.name == p.name; });
    if (it == passes_.end()) {
      passes_.push_back({p.name, std::deque<float>(total_.size() + 1, 0.0f)});
      it = passes_.end() - 1;
    }
    it->ms.back() += float(p.wallMs > 0 ? p.wallMs : p.gpuMs);
  }
  total_.push_back(float(stats.totalMs()));
  for (Series& s : passes_)
    while (s.ms.size() > kFrames) s.ms.pop_front();
  while (total_.size() > kFrames) total_.pop_front();
}

void TimingHistory::draw() const {
  if (total_.empty()) {
    ImGui::TextDisabled("no frame rendered yet");
    return;
  }
  const auto value = [](void* data, int i) { return (*static_cast<const std::deque<float>*>(data))[size_t(i)]; };
  const float height = 1.6f * ImGui::GetFontSize();
  const auto plot = [&](const std::string& name, const std::deque<float>& ms) {
    const float largest = *std::max_element(ms.begin(), ms.end());
    char overlay[96];
    std::snprintf(overlay, sizeof(overlay), "%s  %.1f ms", name.c_str(), double(ms.back()));
    ImGui::PlotLines(("##" + name).c_str(), value, const_cast<std::deque<float>*>(&ms), int(ms.size()), 0, overlay,
                     0.0f, std::max(largest, 1e-3f) * 1.1f, ImVec2(16.0f * ImGui::GetFontSize(), height));
  };
  plot("frame", total_);
  for (const Series& s : passes_) plot(s.name, s.ms);
  ImGui::TextDisabled("ms per pass, last %zu frames", total_.size());
}

namespace {

// Scene, context, image size, what the last frame drew, and any message.
void drawStatus(const ViewerState& state, const PanelInfo& info) {
  ImGui::Text("%s", info.scene->source.filename().string().c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", info.context.c_str());
  ImGui::PopStyleColor();
  ImGui::Text("image %d x %d%s", info.imageWidth, info.imageHeight, info.fixedSize ? " (scripted size)" : "");
  if (const FrameStats* f = info.lastFrame) {
    const LightStats& l = f->lights;
    ImGui::Text("frame %.0f ms%s", f->totalMs(), f->lightsRebuilt ? ", lights rebuilt" : "");
    if (state.settings.indirect() && state.settings.accumulation.enabled)
      ImGui::Text("accumulated %d frames (at most %d)", f->accumulatedFrames, state.settings.accumulation.maxFrames);
    if (state.settings.indirect()) {
      ImGui::TextWrapped("S0 %zu lights: %zu VPLs, %zu emitter samples, %zu point lights", l.inputLights, l.vpls,
                         l.emitterSamples, l.pointLights);
      std::string levels;
      for (size_t i = 0; i < l.lightsPerLevel.size(); ++i)
        if (l.lightsPerLevel[i] > 0) levels += " S" + std::to_string(i) + ":" + std::to_string(l.lightsPerLevel[i]);
      if (state.settings.lightPass.bruteForce)
        ImGui::TextWrapped("brute force: every S0 light at every pixel");
      else
        ImGui::TextWrapped("L = %d, drawn%s", l.levels, levels.c_str());
      if (state.settings.lightPass.overdraw)
        ImGui::Text("overdraw %.1f fragments/pixel (max %u), %.1f shaded, efficiency %.2f", l.rasterizedPerPixel,
                    l.maxRasterized, l.shadedPerPixel, l.efficiency());
    }
    const gl::MemoryRegistry& memory = gl::memory();
    ImGui::Text("GPU memory %s (peak %s)", gl::formatBytes(double(memory.liveBytes())).c_str(),
                gl::formatBytes(double(memory.peakBytes())).c_str());
    if (f->nonFinitePixels > 0) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%u NaN/Inf pixels", f->nonFinitePixels);
  }
  if (!info.message.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.85f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", info.message.c_str());
    ImGui::PopStyleColor();
  }
}

// The AOV shown, grid lights as points, render scale, continuous rendering, screenshot.
void drawViewSection(ViewerState& state, const PanelInfo& info, PanelRequests& requests) {
  const std::vector<std::string> names = aovNames();
  size_t current = 0;
  while (current + 1 < names.size() && parseAov(names[current]) != state.view) ++current;
  if (ImGui::BeginCombo("view", names[current].c_str())) {
    for (size_t i = 0; i < names.size(); ++i)
      if (ImGui::Selectable(names[i].c_str(), i == current)) state.view = parseAov(names[i]);
    ImGui::EndCombo();
  }
  tooltip(
      "final; direct; indirect (unshadowed); irradiance; ratio (raw visibility); visibility (filtered); "
      "overdraw (heat map, turns on counting); emission, albedo, normal, position");
  if (state.view == Aov::Overdraw) state.settings.lightPass.overdraw = true;  // the heat map needs the counts
  const int levels = info.lastFrame ? info.lastFrame->lights.levels : 0;
  bool points = state.pointsLevel > 0;
  // S2 to start with: S1 is dense, the top levels hold a handful of lights.
  if (ImGui::Checkbox("grid lights as points", &points))
    state.pointsLevel = points ? std::clamp(2, 1, std::max(levels, 1)) : 0;
  if (points && levels > 0) {
    state.pointsLevel = std::clamp(state.pointsLevel, 1, levels);
    ImGui::SliderInt("level", &state.pointsLevel, 1, levels, "S%d", ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("point size", &state.pointSize, 1.0f, 16.0f, "%.0f px");
  }
  if (!info.fixedSize)
    ImGui::SliderFloat("render scale", &state.renderScale, 0.25f, 1.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
  tooltip("image pixels per window pixel: below 1 renders faster and is stretched to the window");
  ImGui::Checkbox("render continuously", &state.continuous);
  tooltip("render every frame (live timings); otherwise only after a change");
  if (ImGui::Button("screenshot (F12)")) requests.screenshot = true;
}

// Orbit or fly, reset, and how to navigate.
void drawCameraSection(ViewerState& state, PanelRequests& requests) {
  int mode = state.fly ? 1 : 0;
  ImGui::RadioButton("orbit", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("fly", &mode, 1);
  ImGui::SameLine();
  if (ImGui::Button("reset (R)")) requests.resetCamera = true;
  state.fly = mode == 1;
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped(state.fly ? "drag: look; WASD, Q/E: move (shift: faster); wheel: forward; Tab: orbit"
                               : "drag: orbit; right drag: look; middle or shift drag: pan; wheel: zoom; "
                                 "WASD, Q/E: move; Tab: fly");
  ImGui::PopStyleColor();
}

// The selected punctual light, editable; an edit is requested, not applied here.
void drawLightsSection(ViewerState& state, const Scene& scene, PanelRequests& requests) {
  if (state.lights.empty()) {
    ImGui::TextDisabled("no punctual lights (emissive surfaces light this scene)");
    return;
  }
  const int count = int(state.lights.size());
  state.selectedLight = std::clamp(state.selectedLight, 0, count - 1);
  if (count > 1) ImGui::SliderInt("light", &state.selectedLight, 0, count - 1, "%d", ImGuiSliderFlags_AlwaysClamp);
  PunctualLight& light = state.lights[size_t(state.selectedLight)];
  ImGui::Text("%s (%s)", light.name.empty() ? "unnamed" : light.name.c_str(), lightTypeName(light.type));
  if (drawLight(light, scene.bounds.diagonal())) requests.changedLights.push_back(size_t(state.selectedLight));
  ImGui::TextDisabled("a change rebuilds the VPLs and the hierarchy");
}

// What each owner (a pass, the scene, the viewer's display) holds of the GPU's memory now.
void drawMemorySection() {
  if (!ImGui::BeginTable("memory", 3, ImGuiTableFlags_SizingStretchProp)) return;
  for (const gl::MemoryRegistry::Owner& o : gl::memory().byOwner()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(o.owner.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%s", gl::formatBytes(double(o.bytes)).c_str());
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%zu %s", o.objects, o.objects == 1 ? "object" : "objects");
  }
  ImGui::EndTable();
}

// The per-pass timings in their own window, pinned to the bottom right corner (growing upwards as
// passes appear), so they stay in sight while settings change.
void drawTimingsWindow(const TimingHistory& timings, float em) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x - 0.6f * em, display.y - 0.6f * em), ImGuiCond_Always, ImVec2(1, 1));
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::SetNextWindowCollapsed(display.y < 25.0f * em, ImGuiCond_FirstUseEver);  // a small window needs the room
  if (ImGui::Begin("timings", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) timings.draw();
  ImGui::End();
}

// The scene's animation: play (looping in real time), pause, and the time, which scrubs it.
void drawAnimationSection(ViewerState& state, const SceneAnimation& animation) {
  ImGui::Checkbox("play", &state.playing);
  ImGui::SameLine();
  ImGui::TextDisabled("(%zu channels, %.2f-%.2f s)", animation.channels.size(), animation.start, animation.end);
  double start = animation.start, end = std::max(animation.end, animation.start + 1e-3);
  if (ImGui::SliderScalar("time (s)", ImGuiDataType_Double, &state.time, &start, &end, "%.3f")) state.playing = false;
  ImGui::TextDisabled("the history stays where the lighting did not change (view: history)");
}

}  // namespace

PanelRequests drawPanel(ViewerState& state, const PanelInfo& info) {
  PanelRequests requests;
  const float em = ImGui::GetFontSize();
  // A side panel the window's height, following resizes; it collapses (title bar) or hides (H).
  ImGui::SetNextWindowPos(ImVec2(0.6f * em, 0.6f * em), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(28.0f * em, std::max(ImGui::GetIO().DisplaySize.y - 1.2f * em, 4.0f * em)),
                           ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (ImGui::Begin("lgh-viewer", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize)) {
    ImGui::PushItemWidth(-13.0f * em);  // room for the longest setting names
    drawStatus(state, info);
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) drawViewSection(state, info, requests);
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) drawCameraSection(state, requests);
    if (ImGui::CollapsingHeader("GPU memory by owner", ImGuiTreeNodeFlags_DefaultOpen)) drawMemorySection();
    if (!info.scene->animation.empty() && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen))
      drawAnimationSection(state, info.scene->animation);
    if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen))
      drawLightsSection(state, *info.scene, requests);
    bool settingsChanged = false;
    if (ImGui::CollapsingHeader("Render settings", ImGuiTreeNodeFlags_DefaultOpen))
      settingsChanged |= drawSettings(state.settings, *info.scene, SettingTier::User);
    if (ImGui::CollapsingHeader("Advanced settings"))
      settingsChanged |= drawSettings(state.settings, *info.scene, SettingTier::Advanced);
    if (ImGui::CollapsingHeader("Ablations (docs/settings.md)"))
      settingsChanged |= drawSettings(state.settings, *info.scene, SettingTier::Ablation);
    if (settingsChanged && state.view == Aov::Overdraw) state.settings.lightPass.overdraw = true;
    ImGui::PopItemWidth();
  }
  ImGui::End();
  if (info.timings) drawTimingsWindow(*info.timings, em);
  return requests;
}

}  // namespace lgh
