#include "render/scene/gpu_bvh.h"

#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {
namespace {
gl::Buffer nodeBuffer(const Bvh& bvh) {
  const gl::Label label{passes::kScene, "BVH nodes"};
  switch (bvh.layout) {
    case BvhLayout::Binary:
      return gl::Buffer::fromVector(label, bvh.nodes, 0);
    case BvhLayout::Wide4:
      return gl::Buffer::fromVector(label, bvh.wideNodes, 0);
    case BvhLayout::Compressed8:
      return gl::Buffer::fromVector(label, bvh.compressedNodes, 0);
  }
  return {};
}
}  // namespace

GpuBvh::GpuBvh(const Bvh& bvh)
    : nodes_(nodeBuffer(bvh)),
      triangles_(gl::Buffer::fromVector({passes::kScene, "BVH triangles"}, bvh.triangles, 0)),
      nodeFloats_(nodes_, GL_RGBA32F),
      nodeWords_(nodes_, GL_RGBA32UI),
      triangleWords_(triangles_, GL_RGBA32UI) {}

void GpuBvh::bind() const {
  nodeFloats_.bindTexture(LGH_TEXTURE_BVH_NODE_FLOATS);
  nodeWords_.bindTexture(LGH_TEXTURE_BVH_NODE_WORDS);
  triangleWords_.bindTexture(LGH_TEXTURE_BVH_TRIANGLE_WORDS);
}

}  // namespace lgh
