#pragma once
// Bounding volume hierarchy over scene triangles, built by Embree's BVH builder (rtcBuildBVH: binned SAH
// with spatial splits at high quality) and written into the GPU's node layout: binary, 4-wide or compressed
// 8-wide (shared/bvh_types.h). Our code only defines the nodes and leaves Embree hands back and flattens them;
// the build's quality and speed are Embree's. Built at a scene's load, and again, faster, when its meshes
// move (SceneGpu::follow).

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "shared/bvh_types.h"

namespace lgh {

// The GPU node layouts, in kBvhLayoutChoices' order (= gpu::kBvhLayout*).
enum class BvhLayout { Binary, Wide4, Compressed8 };
inline constexpr const char* kBvhLayoutChoices = "binary|wide4|compressed8";
inline constexpr BvhLayout kBvhLayouts[] = {BvhLayout::Binary, BvhLayout::Wide4, BvhLayout::Compressed8};

// Embree's build quality (RTCBuildQuality): High, binned SAH with spatial splits (a scene's load); Medium,
// binned SAH without; Low, Morton codes (Embree's fastest builder). Faster builds trace slower
// (docs/measurements.md, "The BVH under motion"). In kBvhQualityChoices' order.
enum class BvhQuality { High, Medium, Low };
inline constexpr const char* kBvhQualityChoices = "high|medium|low";

struct BvhBuildStats {
  size_t nodeCount = 0, leafCount = 0;
  size_t triangleReferences = 0;  // leaves' triangles: above the scene's count by the spatial splits
  int maxDepth = 0;               // in nodes of the layout, the root at depth 0
  size_t maxLeafSize = 0;
  double sahCost = 0;  // expected cost per ray, one box or one triangle test each
};

struct Bvh {
  BvhLayout layout = BvhLayout::Binary;
  BvhQuality quality = BvhQuality::High;                // Embree's build quality it was made at
  std::vector<gpu::BvhNode> nodes;                      // binary: nodes[0] is the root (empty without triangles)
  std::vector<gpu::BvhWideNode> wideNodes;              // wide4: wideNodes[0] is the root (empty without triangles)
  std::vector<gpu::BvhCompressedNode> compressedNodes;  // compressed8: [0] is the root (empty without triangles)
  std::vector<gpu::BvhTriangle> triangles;              // leaf order
  // Some triangle's flags carry kBvhTriangleAlphaMasked (set with them, by SceneGpu): only then does a
  // tracing program carry the cut-out test (TracingProgram).
  bool alphaMasked = false;
  BvhBuildStats stats;

  size_t nodeBytes() const {
    return nodes.size() * sizeof(gpu::BvhNode) + wideNodes.size() * sizeof(gpu::BvhWideNode) +
           compressedNodes.size() * sizeof(gpu::BvhCompressedNode);
  }
};

// positions/indices as in Scene (3 indices per triangle). Degenerate triangles are kept (they never
// hit). The depth stays within what the GPU traversal's stack holds (gpu::kBvhStackSize entries);
// throws std::runtime_error where it cannot (or when Embree fails).
Bvh buildBvh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices,
             BvhLayout layout = BvhLayout::Compressed8, BvhQuality quality = BvhQuality::High);

}  // namespace lgh
