#include "render/app/viewer_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "render/gl/debug.h"

namespace lgh {
namespace {

Viewer& viewerOf(GLFWwindow* window) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(window)); }

// Installed before ImGui's backend, which keeps them and calls them after its own handling. Input
// meant for the panel stays there; the rest is queued for the next frame, so a click or key press
// shorter than a (slow) frame still counts.
void scrollCallback(GLFWwindow* window, double, double dy) {
  if (!ImGui::GetIO().WantCaptureMouse) viewerOf(window).onScroll(dy);
}
void keyCallback(GLFWwindow* window, int key, int, int action, int) {
  if (action == GLFW_PRESS && !ImGui::GetIO().WantCaptureKeyboard) viewerOf(window).onKeyPressed(key);
}

// The settings with the image's size: the window's framebuffer times the render scale, or (scripted)
// the settings' own size.
RenderSettings sizedSettings(GLFWwindow* window, const ViewerState& state, bool fixedSize) {
  RenderSettings s = state.settings;
  if (!fixedSize) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    s.image.width = std::max(1, int(std::lround(float(w) * state.renderScale)));
    s.image.height = std::max(1, int(std::lround(float(h) * state.renderScale)));
  }
  return s;
}

bool keyDown(GLFWwindow* window, int key) { return glfwGetKey(window, key) == GLFW_PRESS; }

std::string aovName(Aov aov) {
  for (const std::string& name : aovNames())
    if (parseAov(name) == aov) return name;
  return "?";
}

}  // namespace

Viewer::Viewer(Scene& scene, gl::Context& context, const ViewerState& initial, const ViewerOptions& options)
    : sceneData_(scene),
      context_(context),
      window_(context.window()),
      options_(options),
      state_(initial),
      scene_(scene, initial.settings.bvhLayout),
      renderer_(scene_, sizedSettings(context.window(), initial, false)) {
  if (!window_) throw std::logic_error("Viewer needs the window backend's context");
  state_.lights = scene_.lights();
  glfwSetWindowUserPointer(window_, this);
  glfwSetScrollCallback(window_, scrollCallback);
  glfwSetKeyCallback(window_, keyCallback);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini left in the working directory
  // High-DPI: where window coordinates are pixels (X11), scale the UI by the monitor's content
  // scale; where the framebuffer is already larger than the window (Wayland, macOS), ImGui scales.
  float xScale = 1.0f, yScale = 1.0f;
  glfwGetWindowContentScale(window_, &xScale, &yScale);
  int windowWidth = 1, windowHeight = 1, fbWidth = 1, fbHeight = 1;
  glfwGetWindowSize(window_, &windowWidth, &windowHeight);
  glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
  const float pixelRatio = float(std::max(fbWidth, 1)) / float(std::max(windowWidth, 1));
  const float uiScale = std::clamp(std::max(xScale, yScale) / pixelRatio, 1.0f, 4.0f);
  ImFontConfig font;
  font.SizePixels = std::round(13.0f * uiScale);
  io.Fonts->AddFontDefault(&font);
  ImGui::StyleColorsDark();
  ImGui::GetStyle().ScaleAllSizes(uiScale);
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
  gl::checkErrors("ImGui set-up");

  resetCamera();
  lastTime_ = lastAnimationTime_ = glfwGetTime();
  glfwGetCursorPos(window_, &lastCursor_.x, &lastCursor_.y);
}

Viewer::~Viewer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwSetWindowUserPointer(window_, nullptr);
  glfwSetScrollCallback(window_, nullptr);
  glfwSetKeyCallback(window_, nullptr);
}

void Viewer::onScroll(double steps) { scrollSteps_ += steps; }
void Viewer::onKeyPressed(int key) { keysPressed_.push_back(key); }

void Viewer::run(const std::vector<ScriptCommand>& script) {
  scripted_ = fixedSize_ = !script.empty();
  if (fixedSize_) resetCamera();  // a camera framing the scene takes the scripted aspect ratio
  size_t next = 0;
  int framesLeft = 0;
  while (!glfwWindowShouldClose(window_)) {
    while (scripted_ && framesLeft == 0 && next < script.size()) {
      const ScriptCommand& c = script[next++];
      if (c.kind == ScriptCommand::Kind::Frames) framesLeft = c.number;
      if (!runCommand(c)) return;
    }
    if (scripted_ && framesLeft == 0) scripted_ = fixedSize_ = false;  // no quit: the user takes over
    step(framesLeft > 0);
    framesLeft = std::max(framesLeft - 1, 0);
  }
}

bool Viewer::runCommand(const ScriptCommand& c) {
  using Kind = ScriptCommand::Kind;
  switch (c.kind) {
    case Kind::Frames:
      break;
    case Kind::Set:
      setSetting(state_.settings, c.name, c.value);
      break;
    case Kind::View:
      state_.view = parseAov(c.name);
      break;
    case Kind::Points:
      state_.pointsLevel = c.number;
      break;
    case Kind::Light: {
      if (size_t(c.number) >= state_.lights.size())
        throw std::invalid_argument("script: '" + c.text + "': the scene has " + std::to_string(state_.lights.size()) +
                                    " punctual lights");
      PunctualLight& light = state_.lights[size_t(c.number)];
      if (c.name == "position") light.position = c.vector;
      if (c.name == "direction") light.direction = glm::normalize(c.vector);
      if (c.name == "intensity") light.intensity = c.vector;
      applyLightChanges({size_t(c.number)});
      break;
    }
    case Kind::Time:
      state_.time = c.seconds;
      state_.playing = false;
      playAnimation(0.0);
      break;
    case Kind::Screenshot:
      if (!rendered_ || frameKey() != renderedKey_) step(true);
      writeScreenshot(c.name);
      break;
    case Kind::WindowSize: {
      glfwSetWindowSize(window_, c.size.x, c.size.y);
      // The window system answers asynchronously: wait (briefly) for the new framebuffer size.
      const double deadline = glfwGetTime() + 2.0;
      int w = 0, h = 0;
      do {
        glfwWaitEventsTimeout(0.02);
        glfwGetWindowSize(window_, &w, &h);
      } while ((w != c.size.x || h != c.size.y) && glfwGetTime() < deadline);
      break;
    }
    case Kind::WindowScreenshot:
      windowCapture_ = c.name;
      step(false);  // draws the window, panel included, and captures it before showing it
      break;
    case Kind::Quit:
      if (!options_.quiet) {
        std::printf("last frame (wall ms, glFinish-bracketed)\n");
        for (const auto& p : lastFrame_.passes) std::printf("  %-18s %9.2f\n", p.name.c_str(), p.wallMs);
        std::printf("  %-18s %9.2f\n", "total", lastFrame_.totalMs());
      }
      return false;
  }
  return true;
}

bool Viewer::minimized() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return w == 0 || h == 0;
}

// renderedKey_ is also set by a failed attempt, so a frame that fails is not retried until something changes.
bool Viewer::needsRender() const {
  // A still view keeps rendering while the accumulated history is not full: each frame lowers its error.
  const RenderSettings& s = renderer_.settings();
  const bool accumulating =
      rendered_ && s.indirect() && s.accumulation.enabled && lastFrame_.accumulatedFrames < s.accumulation.maxFrames;
  return state_.continuous || accumulating || frameKey() != renderedKey_;
}

void Viewer::step(bool forceRender) {
  // Idle (nothing to render, or minimized): wait for input rather than spin; ImGui still gets a
  // frame per event and twice a second.
  if (forceRender || !windowCapture_.empty() || (needsRender() && !minimized()))
    glfwPollEvents();
  else
    glfwWaitEventsTimeout(0.5);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  PanelRequests requests;
  if (showPanel_) {
    PanelInfo info;
    info.scene = &sceneData_;
    info.context = context_.description();
    const RenderSettings s = frameSettings();
    info.imageWidth = s.image.width;
    info.imageHeight = s.image.height;
    info.lastFrame = rendered_ ? &lastFrame_ : nullptr;
    info.timings = &timings_;
    info.message = message_;
    info.fixedSize = fixedSize_;
    requests = drawPanel(state_, info);
  }
  const double now = glfwGetTime();
  handleInput(requests);
  applyLightChanges(requests.changedLights);
  playAnimation(std::clamp(now - lastAnimationTime_, 0.0, 0.25));
  lastAnimationTime_ = now;
  if (state_.view == Aov::Overdraw) state_.settings.lightPass.overdraw = true;
  if (state_.settings.image.camera != cameraSetting_ || requests.resetCamera) resetCamera();

  const bool hidden = minimized();
  if (!hidden && (forceRender || needsRender())) {
    try {
      render();
    } catch (const std::exception& e) {
      if (scripted_) throw;
      message_ = std::string("error: ") + e.what();
      renderedKey_ = frameKey();  // do not retry the same failing frame every loop
      std::fprintf(stderr, "lgh-viewer: %s\n", message_.c_str());
    }
  }
  if (rendered_ && !hidden) display();
  present();
  if (requests.screenshot && rendered_) {
    try {
      const std::filesystem::path png = nextScreenshotPath(".png");
      writeScreenshot(png);
      std::filesystem::path exr = png;
      writeScreenshot(exr.replace_extension(".exr"));
      message_ = "wrote " + png.string() + " and .exr";
    } catch (const std::exception& e) {
      message_ = std::string("screenshot failed: ") + e.what();
    }
  }
}

void Viewer::handleInput(PanelRequests& requests) {
  const double now = glfwGetTime();
  // A slow frame must not turn a held key into a leap: movement counts at most a quarter second.
  const float dt = float(std::clamp(now - lastTime_, 0.0, 0.25));
  lastTime_ = now;
  for (int key : keysPressed_) {
    if (key == GLFW_KEY_F12 || key == GLFW_KEY_P) requests.screenshot = true;
    if (key == GLFW_KEY_R) requests.resetCamera = true;
    if (key == GLFW_KEY_TAB) state_.fly = !state_.fly;
    if (key == GLFW_KEY_H || key == GLFW_KEY_F1) showPanel_ = !showPanel_;
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window_, GLFW_TRUE);
  }
  keysPressed_.clear();

  const ImGuiIO& io = ImGui::GetIO();
  glm::dvec2 cursor;
  glfwGetCursorPos(window_, &cursor.x, &cursor.y);
  const glm::vec2 delta(cursor - lastCursor_);
  lastCursor_ = cursor;
  int windowWidth = 1, windowHeight = 1;
  glfwGetWindowSize(window_, &windowWidth, &windowHeight);
  const float sceneSize = std::max(sceneData_.bounds.diagonal(), 1e-6f);
  const bool shift = keyDown(window_, GLFW_KEY_LEFT_SHIFT) || keyDown(window_, GLFW_KEY_RIGHT_SHIFT);
  if (!io.WantCaptureMouse && (delta.x != 0.0f || delta.y != 0.0f)) {
    const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    const bool middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const float radiansPerPixel = 3.14159265f / float(std::max(windowHeight, 1));
    if (middle || (left && shift)) {
      // Pan so that the point at the orbit target follows the cursor.
      const float perPixel = 2.0f * camera_.targetDistance() * std::tan(0.5f * camera_.camera().yfov) /
                             float(std::max(windowHeight, 1)) / sceneSize;
      camera_.pan(-delta.x * perPixel, delta.y * perPixel);
    } else if (left && !state_.fly) {
      camera_.orbit(delta.x * radiansPerPixel, -delta.y * radiansPerPixel);
    } else if (left || right) {
      camera_.look(delta.x * radiansPerPixel, -delta.y * radiansPerPixel);
    }
  }
  if (scrollSteps_ != 0.0) camera_.dolly(float(scrollSteps_));
  scrollSteps_ = 0.0;
  if (!io.WantCaptureKeyboard) {
    glm::vec3 move(0.0f);
    move.z += float(keyDown(window_, GLFW_KEY_W)) - float(keyDown(window_, GLFW_KEY_S));
    move.x += float(keyDown(window_, GLFW_KEY_D)) - float(keyDown(window_, GLFW_KEY_A));
    move.y += float(keyDown(window_, GLFW_KEY_E)) - float(keyDown(window_, GLFW_KEY_Q));
    if (move != glm::vec3(0.0f)) camera_.move(move * (shift ? 0.6f : 0.15f) * dt);  // scene sizes per second
  }
}

void Viewer::applyLightChanges(const std::vector<size_t>& changed) {
  // SceneGpu bumps its lights version; the renderer sees it and rebuilds the VPLs and the hierarchy.
  for (size_t i : changed) scene_.setPunctualLight(i, state_.lights[i]);
}

void Viewer::playAnimation(double dt) {
  const SceneAnimation& animation = sceneData_.animation;
  if (animation.empty()) return;
  if (state_.playing) {
    state_.time += dt;
    const double length = animation.end - animation.start;
    if (state_.time > animation.end)
      state_.time = length > 0 ? animation.start + std::fmod(state_.time - animation.start, length) : animation.start;
  }
  // Posed once per time: the panel's loop runs this every event, mostly with nothing to move.
  if (state_.time == posedTime_) return;
  posedTime_ = state_.time;
  PoseChange change = poseScene(sceneData_, state_.time);
  change.cameras = false;  // the viewer's camera is the user's
  for (size_t i : change.lights) state_.lights[i] = sceneData_.lights[i];
  scene_.follow(change);
}

void Viewer::resetCamera() {
  cameraSetting_ = state_.settings.image.camera;
  camera_.reset(resolveCamera(sceneData_, frameSettings()), sceneData_.bounds.diagonal());
}

RenderSettings Viewer::frameSettings() const {
  RenderSettings s = sizedSettings(window_, state_, fixedSize_);
  if (state_.view == Aov::Overdraw) s.lightPass.overdraw = true;
  return s;
}

std::string Viewer::frameKey() const {
  // Every setting except the display-only ones, the camera's pose and the lights' version.
  RenderSettings s = frameSettings();
  s.image.exposure = 0.0f;
  s.image.toneMap.clear();
  std::ostringstream key;
  key.precision(9);
  visitSettings(s, [&](const auto& value, const SettingInfo& info) { key << info.name << '=' << value << ';'; });
  const Camera& c = camera_.camera();
  key << c.position.x << ',' << c.position.y << ',' << c.position.z << ';' << c.yfov;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) key << ',' << c.orientation[i][j];
  key << ";lights " << scene_.lightsVersion() << ";geometry " << scene_.geometryVersion();
  return key.str();
}

void Viewer::render() {
  const RenderSettings s = frameSettings();
  renderedKey_ = frameKey();
  renderer_.setSettings(s);
  frameView_ = makeCameraView(camera_.camera(), s.image.width, s.image.height);
  lastFrame_ = renderer_.render(frameView_);
  timings_.add(lastFrame_);
  rendered_ = true;
  if (lastFrame_.nonFinitePixels > 0)
    message_ = std::to_string(lastFrame_.nonFinitePixels) + " NaN/Inf pixels were shown black";
}

void Viewer::display() {
  const RenderSettings& s = renderer_.settings();
  if (displayImage_.width != s.image.width || displayImage_.height != s.image.height)
    displayImage_ = DisplayImage(s.image.width, s.image.height);
  DisplayOptions options;
  options.encoding = displayEncodingOf(state_.view);
  options.exposureEV = state_.settings.image.exposure;
  options.toneMap = parseToneMap(state_.settings.image.toneMap);
  // Overdraw over the frame's largest count; history over 64 frames (a pixel at 64 has converged for display).
  options.largestCount = state_.view == Aov::History ? 64u : lastFrame_.lights.maxRasterized;
  displayPass_.execute(renderer_.texture(state_.view), options, displayImage_);
  if (state_.pointsLevel > 0 && s.indirectMethod == IndirectMethod::Lgh && !s.lightPass.bruteForce)
    gridPointsPass_.execute({renderer_.hierarchy(), frameView_, renderer_.gbuffer().position}, state_.pointsLevel,
                            state_.pointSize, displayImage_);
}

void Viewer::present() {
  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fbWidth, fbHeight);
  glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (rendered_ && fbWidth > 0 && fbHeight > 0 && displayImage_.width > 0) {
    // The image fills the window at its aspect ratio (letterboxed when a scripted size differs).
    const float scale =
        std::min(float(fbWidth) / float(displayImage_.width), float(fbHeight) / float(displayImage_.height));
    const int w = int(std::lround(float(displayImage_.width) * scale)),
              h = int(std::lround(float(displayImage_.height) * scale));
    const int x = (fbWidth - w) / 2, y = (fbHeight - h) / 2;
    glBlitNamedFramebuffer(displayImage_.framebuffer.id(), 0, 0, 0, displayImage_.width, displayImage_.height, x, y,
                           x + w, y + h, GL_COLOR_BUFFER_BIT,
                           w == displayImage_.width && h == displayImage_.height ? GL_NEAREST : GL_LINEAR);
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  gl::checkErrors("viewer frame");
  if (!windowCapture_.empty()) {
    const std::filesystem::path path = std::exchange(windowCapture_, {});
    captureWindow(path);
  }
  glfwSwapBuffers(window_);
}

void Viewer::captureWindow(const std::filesystem::path& path) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  std::vector<std::uint8_t> rgb(size_t(width) * size_t(height) * 3);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl::checkErrors("window capture");
  const size_t row = size_t(width) * 3;  // GL rows are bottom-up
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(rgb.begin() + ptrdiff_t(size_t(y) * row), rgb.begin() + ptrdiff_t(size_t(y + 1) * row),
                     rgb.begin() + ptrdiff_t(size_t(height - 1 - y) * row));
  writeDisplayImage(path, width, height, rgb);
  if (!options_.quiet) std::printf("window     %s (%d x %d)\n", path.string().c_str(), width, height);
}

void Viewer::writeScreenshot(const std::filesystem::path& path) {
  if (!rendered_) throw std::runtime_error(path.string() + ": no frame to save yet");
  display();              // the view, exposure or overlay may have changed since the window was last drawn
  if (isHdrFormat(path))  // the AOV shown, as rendered (linear)
    writeImage(path, renderer_.readImage(state_.view), 0.0f, ToneMap::Clamp);
  else  // what the window shows (without the panel), at the image's size
    writeDisplayImage(path, displayImage_.width, displayImage_.height, displayImage_.readRGB());
  if (!options_.quiet)
    std::printf("screenshot %s (%d x %d, view %s, last frame %.0f ms)\n", path.string().c_str(), displayImage_.width,
                displayImage_.height, aovName(state_.view).c_str(), lastFrame_.totalMs());
}

std::filesystem::path Viewer::nextScreenshotPath(const char* extension) const {
  for (int i = 1; i < 100000; ++i) {
    char name[64];
    std::snprintf(name, sizeof(name), "-%03d", i);
    const std::filesystem::path p = options_.screenshotPrefix + name + extension;
    if (!std::filesystem::exists(p)) return p;
  }
  throw std::runtime_error("no free screenshot name for prefix " + options_.screenshotPrefix);
}

}  // namespace lgh
