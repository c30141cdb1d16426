#pragma once
// Gathers the input lights S0 of the hierarchy into one buffer, in this order:
//   point lights  the scene's point lights as omni lights, when there are too many for exact direct
//                 light (e.g. Sponza with 4,096 points)
//   emitters      points on emissive triangles (chosen by power) as oriented direct lights
//   VPLs          oriented VPLs at the diffuse hits of light paths from every light source
//   in:  SceneGpu (BVH, materials, punctual lights), InputLightSettings
//   out: InputLights (gpu::GpuLight buffer and what it holds)

#include <cstdint>

#include "render/gl/buffer.h"
#include "render/passes/vpl_pass.h"
#include "render/scene/scene_gpu.h"
#include "render/settings.h"

namespace lgh {

struct InputLights {
  gl::Buffer lights;  // gpu::GpuLight, `count` of them (at least one slot)
  size_t count = 0;
  size_t pointLights = 0, emitterSamples = 0, vpls = 0;  // how many of each, in buffer order
};

class InputLightsPass {
 public:
  explicit InputLightsPass(const SceneGpu& scene);
  // pointLightsToS0: the scene's point lights go into S0 (and not to the direct pass).
  void execute(const InputLightSettings& settings, bool pointLightsToS0, InputLights& out);
  const VplPass& vplPass() const { return vplPass_; }

 private:
  const SceneGpu& scene_;
  VplPass vplPass_;
};

}  // namespace lgh
