#include "render/gl/program.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace lgh::gl {

const std::map<std::string, std::string>& embeddedShaderSources();  // generated: embedded_shaders.cpp

namespace {

std::string readShaderFile(const std::string& path) {
  if (const char* dir = std::getenv("LGH_SHADER_DIR")) {
    std::ifstream file(std::string(dir) + "/" + path);
    if (file) return std::string(std::istreambuf_iterator<char>(file), {});
  }
  const auto& sources = embeddedShaderSources();
  auto it = sources.find(path);
  if (it == sources.end()) throw std::runtime_error("shader '" + path + "' not found in glsl/");
  return it->second;
}

// Expands includes recursively. Each file gets a source-string number so that compiler messages
// ("0:12(3): error ...") can be traced back; the numbering is listed in the error text.
class ShaderExpander {
 public:
  std::string expand(const std::string& path, const Defines& defines) {
    std::string text = include(path, /*isRoot=*/true, defines);
    return text;
  }
  std::string fileTable() const {
    std::string table;
    for (size_t i = 0; i < files_.size(); ++i) table += "  " + std::to_string(i) + " = glsl/" + files_[i] + "\n";
    return table;
  }

 private:
  std::string include(const std::string& path, bool isRoot, const Defines& defines) {
    if (!included_.insert(path).second) return "";
    const int fileId = int(files_.size());
    files_.push_back(path);
    std::istringstream lines(readShaderFile(path));
    std::string out, line;
    int lineNumber = 0;
    while (std::getline(lines, line)) {
      ++lineNumber;
      if (line.rfind("#version", 0) == 0) {
        if (!isRoot) throw std::runtime_error("glsl/" + path + ": #version in an included file");
        out += line + "\n";
        for (const auto& [name, value] : defines) out += "#define " + name + " " + value + "\n";
        out += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(fileId) + "\n";
        continue;
      }
      // `#include "x"` is ours to resolve; `#include <x>` only appears in C++-only sections of shared
      // headers (#ifdef __cplusplus), which the GLSL preprocessor skips.
      const size_t at = line.find("#include \"");
      if (at != std::string::npos && line.find_first_not_of(" \t") == at) {
        const size_t open = line.find('"', at), close = line.find('"', open + 1);
        if (open == std::string::npos || close == std::string::npos)
          throw std::runtime_error("glsl/" + path + ":" + std::to_string(lineNumber) + ": malformed #include");
        out += include(line.substr(open + 1, close - open - 1), false, defines);
        out += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(fileId) + "\n";
        continue;
      }
      out += line + "\n";
    }
    if (!isRoot) out = "#line 1 " + std::to_string(fileId) + "\n" + out;
    return out;
  }

  std::set<std::string> included_;
  std::vector<std::string> files_;
};

GLuint compileStage(GLenum stage, const std::string& path, const Defines& defines) {
  ShaderExpander expander;
  const std::string source = expander.expand(path, defines);
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw std::runtime_error("compiling glsl/" + path + " failed:\n" + log + "source strings:\n" +
                             expander.fileTable());
  }
  return shader;
}

GLuint linkProgram(std::initializer_list<GLuint> shaders, const std::string& label) {
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw std::runtime_error("linking " + label + " failed:\n" + log);
  }
  glObjectLabel(GL_PROGRAM, program, -1, label.c_str());
  return program;
}

}  // namespace

std::string expandShaderSource(const std::string& path, const Defines& defines) {
  return ShaderExpander().expand(path, defines);
}

Program Program::compute(const std::string& path, const Defines& defines) {
  return Program(linkProgram({compileStage(GL_COMPUTE_SHADER, path, defines)}, path));
}

Program Program::graphics(const std::string& vertexPath, const std::string& fragmentPath, const Defines& defines) {
  const GLuint vs = compileStage(GL_VERTEX_SHADER, vertexPath, defines);
  GLuint fs = 0;
  try {
    fs = compileStage(GL_FRAGMENT_SHADER, fragmentPath, defines);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  return Program(linkProgram({vs, fs}, vertexPath + " + " + fragmentPath));
}

GLint Program::location(const char* name) const {
  auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id(), name);
  locations_.emplace(name, loc);
  return loc;
}

void Program::dispatch1D(size_t invocations, unsigned localSize) const {
  if (invocations == 0) return;
  const size_t groups = (invocations + localSize - 1) / localSize;
  constexpr size_t kMaxGroups = 65535;
  const size_t groupsX = groups < kMaxGroups ? groups : kMaxGroups;
  const size_t groupsY = (groups + groupsX - 1) / groupsX;
  use();
  glDispatchCompute(GLuint(groupsX), GLuint(groupsY), 1);
}

void Program::dispatch2D(int width, int height, glm::uvec2 localSize) const {
  if (width <= 0 || height <= 0) return;
  use();
  glDispatchCompute((GLuint(width) + localSize.x - 1) / localSize.x, (GLuint(height) + localSize.y - 1) / localSize.y,
                    1);
}

}  // namespace lgh::gl
