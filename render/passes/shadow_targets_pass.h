#pragma once
// Shadow-ray targets (docs/design.md §5). A shadow ray towards a selected grid light aims at one of
// its input lights, drawn with probability equal to that light's share of the grid light's importance
// (lgh/cluster_shares.h), so that its expected visibility is the cluster's share-weighted visibility
// of real lights, not that of a point inside the cluster (which may lie inside a wall).
//   in:  ShadowTargetsInputs: input lights S0, the hierarchy (grid lights and each level's vertex lookup);
//        races m, frame seed
//   out: ShadowTargets: for merged grid light g, targets[g m + j] is the input light race j drew
// New draws every frame (glsl/shadow_targets.comp: two kernels per level over S0 and each level's
// sources, O(8 m) atomics per source), so an image accumulated over frames sees every light.

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/passes/lgh_build_pass.h"

namespace lgh {

struct ShadowTargets {
  gl::Buffer targets;  // uint input-light index per (grid light, race); gpu::kNoLight where none
  unsigned races = 0;  // m; 0: no targets drawn, rays aim at the cluster's jittered centre
};

struct ShadowTargetsInputs {
  const gl::Buffer& inputLights;  // S0 (gpu::GpuLight), `inputLightCount` valid
  size_t inputLightCount = 0;
  const GpuHierarchy& hierarchy;
};

class ShadowTargetsPass {
 public:
  ShadowTargetsPass();
  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  void execute(const ShadowTargetsInputs& in, unsigned races, unsigned frameSeed, ShadowTargets& out);

 private:
  // Runs the race (or the resolve) of `level` over its sources.
  void runLevel(const gl::Program& fromLights, const gl::Program& fromGridLights, const ShadowTargetsInputs& in,
                int level, unsigned races, unsigned seed);

  gl::Program raceFromLights_, resolveFromLights_, raceFromGridLights_, resolveFromGridLights_;
  gl::Buffer raceTimes_, gridParams_;
  size_t maxBlockBytes_ = 0;
};

}  // namespace lgh
