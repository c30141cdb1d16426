#pragma once
// What the light pass's culled volumes are tested against (LightVolumePass, volume culling on):
//   * a depth-stencil target in the pass's (tiled) layout: depth = each surface's volumeDepth (clip w
//     mapped to nearW / w, reversed, glsl/shared/light_levels.h), stencil = its depth slice (of its
//     cullingDepth, w / (w + scene size));
//   * a max-cullingDepth pyramid, for skipping volumes hidden behind every surface under them;
//   * the volumes of one draw sorted by the slice of their nearest depth, drawn slice by slice with that
//     slice as stencil reference; spheres that reach the eye plane in a bucket of their own, drawn as
//     the back faces of icosahedra.
// Per pixel the depth test (LEQUAL: the volume's far depth not nearer than the surface) rejects surfaces
// behind a volume and the stencil test (reference <= stencil) surfaces in front of its slice, both
// before shading. Depth draws use GL_ZERO_TO_ONE (float keeps nearW / w's precision).
// Only fragments whose surface is farther than 2R from the light are rejected: their weight is zero.

#include <glm/glm.hpp>

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/gl/resource.h"
#include "render/gl/texture.h"

namespace lgh {

// Slices of culling depth: the stencil's resolution in depth (at most gpu::kMaxCullingSlices).
inline constexpr unsigned kCullingSlices = 255;

class VolumeCulling {
 public:
  VolumeCulling();

  // The depth-stencil texture for a target of `size` (reallocated when the size changes).
  const gl::Texture2D& depthStencil(glm::ivec2 size);
  // With the framebuffer holding depthStencil() bound and cleared: writes the surfaces' culling depth
  // and slice from `position` (the target's layout), then the max pyramid. Leaves depth and stencil
  // tests off.
  void prepare(const gl::Texture2D& position, float sceneSize);
  // Sorts grid lights [first, first + count) by slice, for drawSorted().
  struct SortInputs {
    const gl::Buffer* gridLights;
    size_t first, count;
    float alpha, topCellSize, sceneSize;
    int levels;
  };
  void sortBySlice(const SortInputs& inputs);
  // Binds the pyramid to texture unit 2 (light_volume.vert reads it).
  void bindPyramid() const;
  // The sorted volumes: the crossing spheres' icosahedra (front faces culled), then the octagons
  // (8-vertex strips), one indirect draw per slice with its stencil reference; the light index comes
  // from the vertex attribute 0 (LGH_SORTED_LIGHTS in light_volume.vert). Needs the depth test and
  // GL_ZERO_TO_ONE set up by the caller; sets and restores the stencil test, leaves face culling off.
  void drawSorted() const;
  // Frees the textures and buffers (made again when next needed).
  void release();

 private:
  void writeDepthAndSlices(const gl::Texture2D& position, float sceneSize);
  void buildPyramid(const gl::Texture2D& position, float sceneSize);

  bool stencilExport_;          // GL_ARB_shader_stencil_export: slices written with the depth, in one pass
  gl::Texture2D depthStencil_;  // DEPTH32F_STENCIL8
  gl::Texture2D pyramid_;       // R32F, every level
  gl::Program depthProgram_, boundaryProgram_, pyramidProgram_, sortProgram_;
  gl::Buffer sliceCounts_, sliceAndRank_, commands_, sortedLights_;
  gl::VertexArrayHandle emptyVertexArray_, sortedVertexArray_;
};

}  // namespace lgh
