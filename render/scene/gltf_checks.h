#pragma once
// What every part of the glTF loader (render/scene/gltf_*.cpp) uses to check numbers and report
// problems. Internal to the loader: its interface is loadScene (scene.h).
//
// A fatal problem is thrown as FileProblem, worded without the file's path: the helpers then need
// no path, and loadScene adds it once to make the SceneLoadError "<path>: <problem>".
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace lgh::gltf {

struct FileProblem : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& problem) { throw FileProblem(problem); }

// "node 3 'lamp'": how messages name an object of the file (the name only where it has one).
inline std::string label(const char* kind, size_t index, const std::string& name) {
  std::string s = std::string(kind) + " " + std::to_string(index);
  if (!name.empty()) s += " '" + name + "'";
  return s;
}

// A number for a message, short at any magnitude (std::to_string prints 1e39 with 40 digits, 1e-9 as 0.000000).
inline std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// True when `v` survives the conversion to float (finite and within float's range). Numbers are
// checked where they become float: a JSON value such as 1e39 is a finite double but an infinite float.
inline bool fitsFloat(double v) { return std::isfinite(v) && std::abs(v) <= double(std::numeric_limits<float>::max()); }

// Collects one kind of recoverable problem so a file with thousands of them gives one warning line.
struct WarningGroup {
  explicit WarningGroup(std::string what) : text(std::move(what)) {}
  std::string text;
  size_t count = 0;
  std::vector<std::string> examples;
  void add(const std::string& example) {
    ++count;
    if (examples.size() < 5 && std::find(examples.begin(), examples.end(), example) == examples.end())
      examples.push_back(example);
  }
  void flush(std::vector<std::string>& out) const {
    if (count == 0) return;
    std::string s = text + " (" + std::to_string(count) + "x: ";
    for (size_t i = 0; i < examples.size(); ++i) s += (i ? ", " : "") + examples[i];
    if (count > examples.size()) s += ", ...";
    out.push_back(s + ")");
  }
};

}  // namespace lgh::gltf
