#pragma once
// The BVH on the GPU: its nodes and triangles in buffers, read by the traversal (shared/bvh_traverse.glsl)
// as texels, through a float and an integer view of the nodes and an integer view of the triangles. (Texels, not SSBO
// words: llvmpipe fetches texels with vector gathers, but loads SSBO words one invocation at a time, and that made the
// traversal 1.4-1.6x slower; docs/measurements.md, "The BVH". GPUs read both through their caches.)

#include "render/gl/buffer.h"
#include "render/gl/texture.h"
#include "render/scene/bvh.h"

namespace lgh {

class GpuBvh {
 public:
  GpuBvh() = default;
  explicit GpuBvh(const Bvh& bvh);

  // At the LGH_TEXTURE_BVH_* units, where every shader that traces reads it.
  void bind() const;

 private:
  gl::Buffer nodes_, triangles_;
  gl::BufferTexture nodeFloats_, nodeWords_, triangleWords_;
};

}  // namespace lgh
