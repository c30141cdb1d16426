#pragma once
// Direct light from the scene's punctual lights, exact: one ray-traced shadow ray per light per pixel.
//   in:  GBuffer, SceneGpu (punctual lights, BVH)
//   out: direct radiance (RGBA32F)

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/passes/gbuffer_pass.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"

namespace lgh {

class DirectLightPass {
 public:
  DirectLightPass();
  // skipPointLights: point lights are shaded elsewhere (through the LGH, when there are many).
  void execute(const SceneGpu& scene, const GBuffer& gbuffer, bool shadows, bool skipPointLights, gl::Texture2D& out);

 private:
  TracingProgram program_;
  // The lights shaded here when point lights are skipped (uploaded when the scene's lights change,
  // bound in place of the scene's).
  gl::Buffer nonPointLights_;
  size_t nonPointLightCount_ = 0;
  bool nonPointLightsUploaded_ = false;
  unsigned nonPointLightsVersion_ = 0;  // SceneGpu::lightsVersion() they were taken from
};

}  // namespace lgh
