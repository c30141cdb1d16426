#pragma once
// A compute program that traces rays through a scene's BVH (shared/bvh_traverse.glsl): compiled for the
// scene's node layout (LGH_BVH_LAYOUT = gpu::kBvhLayout*), once per layout it meets, the first time it
// traces a scene of that layout. The passes that trace hold one instead of a gl::Program.

#include <array>
#include <string>

#include "render/gl/program.h"
#include "render/scene/scene_gpu.h"

namespace lgh {

class TracingProgram {
 public:
  explicit TracingProgram(std::string path, gl::Defines defines = {});
  // The program for `scene`'s BVH layout.
  const gl::Program& operator()(const SceneGpu& scene) { return forLayout(scene.bvh().layout); }
  const gl::Program& forLayout(BvhLayout layout);

 private:
  std::string path_;
  gl::Defines defines_;
  std::array<gl::Program, std::size(kBvhLayouts)> programs_;  // by BvhLayout
};

}  // namespace lgh
