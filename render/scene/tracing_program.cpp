#include "render/scene/tracing_program.h"

#include <utility>

namespace lgh {

TracingProgram::TracingProgram(std::string path, gl::Defines defines)
    : path_(std::move(path)), defines_(std::move(defines)) {}

const gl::Program& TracingProgram::forLayout(BvhLayout layout) {
  gl::Program& program = programs_.at(size_t(layout));
  if (!program) {
    gl::Defines defines = defines_;
    defines.emplace_back("LGH_BVH_LAYOUT", std::to_string(int(layout)));
    program = gl::Program::compute(path_, defines);
  }
  return program;
}

}  // namespace lgh
