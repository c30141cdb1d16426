#include "render/scene/gpu_bvh.h"

#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {

GpuBvh::GpuBvh(const Bvh& bvh)
    : nodes_(bvh.layout == BvhLayout::Wide4 ? gl::Buffer::fromVector({passes::kScene, "BVH nodes"}, bvh.wideNodes, 0)
                                            : gl::Buffer::fromVector({passes::kScene, "BVH nodes"}, bvh.nodes, 0)),
      triangles_(gl::Buffer::fromVector({passes::kScene, "BVH triangles"}, bvh.triangles, 0)),
      nodeFloats_(nodes_, GL_RGBA32F),
      nodeWords_(nodes_, GL_RGBA32UI),
      triangleFloats_(triangles_, GL_RGBA32F),
      triangleWords_(triangles_, GL_RGBA32UI) {}

void GpuBvh::bind() const {
  nodeFloats_.bindTexture(LGH_TEXTURE_BVH_NODE_FLOATS);
  nodeWords_.bindTexture(LGH_TEXTURE_BVH_NODE_WORDS);
  triangleFloats_.bindTexture(LGH_TEXTURE_BVH_TRIANGLE_FLOATS);
  triangleWords_.bindTexture(LGH_TEXTURE_BVH_TRIANGLE_WORDS);
}

}  // namespace lgh
