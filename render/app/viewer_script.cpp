#include "render/app/viewer_script.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "render/image_io.h"
#include "render/renderer.h"
#include "render/text_parse.h"

namespace lgh {
namespace {

std::string trim(const std::string& s) {
  const size_t first = s.find_first_not_of(" \t\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\n") - first + 1);
}

// Splits "key=value" at the first '='; the value is empty when there is none.
std::pair<std::string, std::string> keyValue(const std::string& word) {
  const size_t eq = word.find('=');
  if (eq == std::string::npos) return {word, ""};
  return {trim(word.substr(0, eq)), trim(word.substr(eq + 1))};
}

bool parseVector(const std::string& text, glm::vec3& out) {
  std::stringstream in(text);
  std::string part;
  int i = 0;
  while (std::getline(in, part, ',')) {
    if (i == 3 || !parseNumber(trim(part), out[i])) return false;
    ++i;
  }
  return i == 3;
}

}  // namespace

std::vector<ScriptCommand> parseScript(const std::string& script) {
  std::vector<ScriptCommand> commands;
  std::stringstream in(script);
  std::string text;
  RenderSettings scratch;  // `set` commands are tried on a copy so bad names and values fail here
  while (std::getline(in, text, ';')) {
    text = trim(text);
    if (text.empty()) continue;
    ScriptCommand c;
    c.text = text;
    const auto fail = [&](const std::string& problem) {
      return std::invalid_argument("script: '" + text + "': " + problem);
    };
    const size_t space = text.find_first_of(" \t");
    const auto [key, value] = keyValue(text.substr(0, space));
    const std::string rest = space == std::string::npos ? "" : trim(text.substr(space));
    try {
      if (key == "frames") {
        c.kind = ScriptCommand::Kind::Frames;
        if (!parseNumber(value, c.number) || c.number < 1) throw fail("expects frames=N with N >= 1");
      } else if (key == "set") {
        c.kind = ScriptCommand::Kind::Set;
        std::tie(c.name, c.value) = keyValue(rest);
        if (rest.find('=') == std::string::npos) throw fail("expects set NAME=VALUE");
        setSetting(scratch, c.name, c.value);
      } else if (key == "view") {
        c.kind = ScriptCommand::Kind::View;
        c.name = value;
        parseAov(value);  // throws with the list of AOVs
      } else if (key == "points") {
        c.kind = ScriptCommand::Kind::Points;
        if (!parseNumber(value, c.number) || c.number < 0) throw fail("expects points=L with L >= 0 (0: off)");
      } else if (key == "light") {
        c.kind = ScriptCommand::Kind::Light;
        if (!parseNumber(value, c.number) || c.number < 0) throw fail("expects light=I with a light index I >= 0");
        std::string vector;
        std::tie(c.name, vector) = keyValue(rest);
        if (c.name != "position" && c.name != "direction" && c.name != "intensity")
          throw fail("expects light=I position=X,Y,Z (or direction=X,Y,Z or intensity=R,G,B)");
        if (!parseVector(vector, c.vector)) throw fail("'" + vector + "' is not three comma-separated numbers");
        if (c.name == "direction" && glm::length(c.vector) == 0.0f) throw fail("a direction must not be zero");
      } else if (key == "time") {
        c.kind = ScriptCommand::Kind::Time;
        if (!parseNumber(value, c.seconds) || !std::isfinite(c.seconds)) throw fail("expects time=T in seconds");
      } else if (key == "screenshot") {
        c.kind = ScriptCommand::Kind::Screenshot;
        c.name = value;
        if (value.empty()) throw fail("expects screenshot=FILE");
        checkImagePath(value);
      } else if (key == "window-screenshot") {
        c.kind = ScriptCommand::Kind::WindowScreenshot;
        c.name = value;
        if (value.empty()) throw fail("expects window-screenshot=FILE");
        checkImagePath(value);
        if (isHdrFormat(value)) throw fail("the window is 8-bit: write .png, .jpg, .tif or .bmp");
      } else if (key == "window") {
        c.kind = ScriptCommand::Kind::WindowSize;
        const size_t x = value.find('x');
        if (x == std::string::npos || !parseNumber(value.substr(0, x), c.size.x) ||
            !parseNumber(value.substr(x + 1), c.size.y) || c.size.x < 1 || c.size.y < 1 || c.size.x > 16384 ||
            c.size.y > 16384)
          throw fail("expects window=WxH (1 to 16384 each)");
      } else if (key == "quit" && value.empty()) {
        c.kind = ScriptCommand::Kind::Quit;
      } else {
        throw fail(
            "unknown command (frames=N, set NAME=VALUE, view=AOV, points=L, light=I position=X,Y,Z, time=T, "
            "screenshot=FILE, window-screenshot=FILE, window=WxH, quit)");
      }
      if (c.kind != ScriptCommand::Kind::Set && c.kind != ScriptCommand::Kind::Light && !rest.empty())
        throw fail("unexpected '" + rest + "'");
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      throw what.rfind("script:", 0) == 0 ? e : fail(what);
    } catch (const std::runtime_error& e) {  // checkImagePath
      throw fail(e.what());
    }
    commands.push_back(c);
  }
  return commands;
}

}  // namespace lgh
