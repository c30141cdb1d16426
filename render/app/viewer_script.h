#pragma once
// The viewer's scripted mode (--script): a fixed sequence of frames, parameter changes and
// screenshots, so a test (or a README screenshot) can drive the interactive viewer without input.
//
//   frames=N                   render and show N frames
//   set NAME=VALUE             a render setting by its lgh-render name (alpha, shadow-samples, ...)
//   view=AOV                   what the window shows: final, direct, indirect, ratio, overdraw, ...
//   points=L                   draw the grid lights of level L as points (0: off)
//   light=I position=X,Y,Z     move punctual light I (also direction=X,Y,Z, intensity=R,G,B)
//   time=T                     the scene's animation at T seconds (paused)
//   screenshot=FILE            .png/.jpg: the image the window shows; .exr/.hdr: that AOV, linear
//   window-screenshot=FILE     the whole window, panel included (.png/.jpg)
//   window=WxH                 resize the window (the scripted image keeps its size, letterboxed)
//   quit                       exit (without it the viewer stays open for interaction)
// Commands are separated by ';'. Everything is checked before the window opens.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/settings.h"

namespace lgh {

struct ScriptCommand {
  enum class Kind { Frames, Set, View, Points, Light, Time, Screenshot, WindowScreenshot, WindowSize, Quit };
  Kind kind = Kind::Quit;
  std::string text;     // the command as written, for messages
  int number = 0;       // Frames: N; Points: L; Light: I
  std::string name;     // Set: setting; View: AOV; Light: position|direction|intensity; Screenshot: file
  std::string value;    // Set: value
  glm::vec3 vector{0};  // Light
  double seconds = 0;   // Time
  glm::ivec2 size{0};   // WindowSize
};

// Throws std::invalid_argument("script: '<command>': <problem>").
std::vector<ScriptCommand> parseScript(const std::string& script);

}  // namespace lgh
