#pragma once
// A compute program that traces rays through a scene's BVH (shared/bvh_traverse.glsl): compiled for the
// BVH's node layout (LGH_BVH_LAYOUT = gpu::kBvhLayout*) and for whether any of its triangles is alpha-masked
// (LGH_BVH_ALPHA_MASKED: the cut-out test, which SIMD lanes run once a ray even where no lane needs it,
// is left out of a scene without them), once per variant it meets. The passes that trace hold one
// instead of a gl::Program.

#include <array>
#include <string>

#include "render/gl/program.h"
#include "render/scene/scene_gpu.h"

namespace lgh {

class TracingProgram {
 public:
  explicit TracingProgram(std::string path, gl::Defines defines = {});
  // The program for `scene`'s BVH.
  const gl::Program& operator()(const SceneGpu& scene) { return forBvh(scene.bvh()); }
  const gl::Program& forBvh(const Bvh& bvh);

 private:
  std::string path_;
  gl::Defines defines_;
  std::array<gl::Program, 2 * std::size(kBvhLayouts)> programs_;  // by BvhLayout, then alpha-masked
};

}  // namespace lgh
