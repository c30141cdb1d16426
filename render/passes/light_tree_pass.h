#pragma once
// The light tree of real-time stochastic lightcuts (Lin & Yuksel 2020, §3.1 and §4; docs/design.md
// §12), rebuilt whenever S0 is:
//   in:  the input lights S0 (gpu::GpuLight buffer, any count that fits one storage block's tree)
//   out: GpuLightTree: a perfect binary tree of gpu::GpuLightTreeNode as a 1-based heap over the lights in
//        Morton order, and the lights' bounds (the cuts' distance floor reads them on the GPU)
// Steps (each a profiler scope when a profiler is given, as the paper's Table 1): bounds (lgh_bounds.comp),
// Morton codes, sort (gl::RadixSort, stable: the same tree every run), leaves, internal levels
// (light_tree.comp). The CPU reference is lgh::buildLightTree (lgh/light_tree.h).

#include <cstddef>
#include <vector>

#include "render/gl/buffer.h"
#include "render/gl/profiler.h"
#include "render/gl/program.h"
#include "render/gl/radix_sort.h"
#include "render/pass_names.h"
#include "shared/light_tree_types.h"

namespace lgh {

struct GpuLightTree {
  gl::Buffer nodes;        // gpu::GpuLightTreeNode[2 leafCount]; node 0 unused
  gl::Buffer bounds;       // gpu::LghBoundsResult of S0 (all lights' box: the Morton box)
  unsigned leafCount = 0;  // 2^(L-1); 0: no lights, no tree
  int levels = 0;          // L
  size_t lightCount = 0;
  std::vector<gpu::GpuLightTreeNode> download() const;  // for tests
};

// Levels of the perfect tree over `lightCount` lights: ceil(log2 N) + 1 (0 for none).
int lightTreeLevelsFor(size_t lightCount);

class LightTreePass {
 public:
  LightTreePass();
  // Throws std::runtime_error when the tree would not fit one storage block (over 2^21 leaves).
  void execute(const gl::Buffer& lights, size_t lightCount, GpuLightTree& out, gl::Profiler* profiler = nullptr);

 private:
  gl::Program bounds_, build_;
  gl::RadixSort sort_{passes::kLightTreeBuild};
  gl::Buffer keys_, values_;  // Morton codes and S0 indices, sorted together
};

}  // namespace lgh
