#include "render/scene/tracing_program.h"

#include <utility>

namespace lgh {

TracingProgram::TracingProgram(std::string path, gl::Defines defines)
    : path_(std::move(path)), defines_(std::move(defines)) {}

const gl::Program& TracingProgram::forBvh(const Bvh& bvh) {
  gl::Program& program = programs_.at(2 * size_t(bvh.layout) + (bvh.alphaMasked ? 1 : 0));
  if (!program) {
    gl::Defines defines = defines_;
    defines.emplace_back("LGH_BVH_LAYOUT", std::to_string(int(bvh.layout)));
    defines.emplace_back("LGH_BVH_ALPHA_MASKED", bvh.alphaMasked ? "1" : "0");
    program = gl::Program::compute(path_, defines);
  }
  return program;
}

}  // namespace lgh
