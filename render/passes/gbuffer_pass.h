#pragma once
// Rasterizes the scene into the deferred G-buffer.
//   in:  SceneGpu, frame uniforms (bound at LGH_UBO_FRAME)
//   out: GBuffer (world position, shading normal, albedo, emission, depth)

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/scene/scene_gpu.h"

namespace lgh {

struct GBuffer {
  GBuffer() = default;
  GBuffer(int width, int height);
  int width = 0, height = 0;
  gl::Texture2D position;  // RGBA32F: xyz world position, w = 1 on geometry, 0 on background
  gl::Texture2D normal;    // RGBA16F: unit shading normal facing the camera
  gl::Texture2D albedo;    // RGBA16F: linear diffuse albedo
  gl::Texture2D emission;  // RGBA16F: emitted radiance
  gl::Texture2D depth;     // DEPTH_COMPONENT32F
  gl::Framebuffer framebuffer;
  // Binds position/normal/albedo/emission to texture units 0..3 (see glsl/shared/gbuffer.glsl).
  void bindForReading() const;
};

class GBufferPass {
 public:
  GBufferPass();
  void execute(const SceneGpu& scene, GBuffer& out) const;

 private:
  gl::Program program_;
};

}  // namespace lgh
