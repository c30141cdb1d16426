#include "render/scene/bvh.h"

#include <embree3/rtcore.h>
#include <embree3/rtcore_builder.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

namespace lgh {
namespace {

constexpr unsigned kMaxLeafSize = 8;  // compressed8: gpu::kBvhCompressedMaxLeafSize
constexpr unsigned kMaxWidth = gpu::kBvhCompressedWidth;
// The traversals' stacks: binary pushes at most one node per level, 4-wide at most three net (four
// children entered, one taken at once), compressed 8-wide one (its node and the slots left), so these
// depths keep them within gpu::kBvhStackSize.
constexpr unsigned kMaxBinaryDepth = gpu::kBvhStackSize - 4;
constexpr unsigned kMaxWideDepth = (gpu::kBvhStackSize - 4) / (gpu::kBvhWidth - 1);
constexpr unsigned kMaxCompressedDepth = gpu::kBvhStackSize - 1;  // one entry per level above the current

unsigned maxDepth(BvhLayout layout) {
  return layout == BvhLayout::Binary  ? kMaxBinaryDepth
         : layout == BvhLayout::Wide4 ? kMaxWideDepth
                                      : kMaxCompressedDepth;
}
unsigned maxWidth(BvhLayout layout) {
  return layout == BvhLayout::Binary ? 2 : layout == BvhLayout::Wide4 ? gpu::kBvhWidth : gpu::kBvhCompressedWidth;
}
unsigned maxLeafSize(BvhLayout layout) {
  return layout == BvhLayout::Compressed8 ? gpu::kBvhCompressedMaxLeafSize : kMaxLeafSize;
}

struct Box {
  glm::vec3 min{std::numeric_limits<float>::max()}, max{-std::numeric_limits<float>::max()};
  void extend(const glm::vec3& p) { min = glm::min(min, p), max = glm::max(max, p); }
  bool empty() const { return min.x > max.x; }
  float area() const {
    if (empty()) return 0.0f;
    const glm::vec3 e = max - min;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

Box toBox(const RTCBounds& b) { return {{b.lower_x, b.lower_y, b.lower_z}, {b.upper_x, b.upper_y, b.upper_z}}; }

// Grows a box outward by a few ulps so that float slab tests on the GPU cannot miss a triangle lying
// exactly in a box face (axis-aligned geometry makes flat boxes everywhere in real scenes).
Box padded(const Box& b) {
  Box out = b;
  for (int a = 0; a < 3; ++a) {
    const float scale = std::max(std::abs(b.min[a]), std::abs(b.max[a])) + (b.max[a] - b.min[a]);
    const float pad = scale * 4.0f * std::numeric_limits<float>::epsilon() + std::numeric_limits<float>::min();
    out.min[a] -= pad;
    out.max[a] += pad;
  }
  return out;
}

// The tree Embree builds, in its thread-local memory (freed with the RTCBVH; no destructors run).
struct BuildNode {
  bool leaf;
};
struct InnerNode : BuildNode {
  unsigned childCount = 0;
  BuildNode* children[kMaxWidth] = {};
  RTCBounds bounds[kMaxWidth] = {};
};
struct LeafNode : BuildNode {
  unsigned count = 0;
  std::uint32_t triangles[kMaxLeafSize] = {};
};

struct BuildContext {
  const std::vector<glm::vec3>& positions;
  const std::vector<std::uint32_t>& indices;
  unsigned maxLeafSize;
  std::atomic<bool> oversizedLeaf{false};
};

void* createNode(RTCThreadLocalAllocator allocator, unsigned int childCount, void*) {
  void* memory = rtcThreadLocalAlloc(allocator, sizeof(InnerNode), 16);
  InnerNode* node = new (memory) InnerNode;
  node->leaf = false;
  node->childCount = childCount;
  return node;
}

void setNodeChildren(void* node, void** children, unsigned int childCount, void*) {
  for (unsigned i = 0; i < childCount; ++i)
    static_cast<InnerNode*>(node)->children[i] = static_cast<BuildNode*>(children[i]);
}

void setNodeBounds(void* node, const RTCBounds** bounds, unsigned int childCount, void*) {
  for (unsigned i = 0; i < childCount; ++i) static_cast<InnerNode*>(node)->bounds[i] = *bounds[i];
}

void* createLeaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives, size_t count, void* user) {
  void* memory = rtcThreadLocalAlloc(allocator, sizeof(LeafNode), 16);
  LeafNode* leaf = new (memory) LeafNode;
  leaf->leaf = true;
  BuildContext& context = *static_cast<BuildContext*>(user);
  if (count > context.maxLeafSize) context.oversizedLeaf = true;
  leaf->count = unsigned(std::min<size_t>(count, context.maxLeafSize));
  for (unsigned i = 0; i < leaf->count; ++i) leaf->triangles[i] = primitives[i].primID;
  return leaf;
}

// A spatial split of one triangle reference: the bounds of the triangle's parts on each side of the plane
// (its vertices there and where its edges cross it), within the reference's bounds (already clipped by
// earlier splits).
void splitPrimitive(const RTCBuildPrimitive* primitive, unsigned int dimension, float position, RTCBounds* left,
                    RTCBounds* right, void* user) {
  const BuildContext& context = *static_cast<const BuildContext*>(user);
  glm::vec3 v[3];
  for (int k = 0; k < 3; ++k) v[k] = context.positions[context.indices[3 * size_t(primitive->primID) + k]];
  Box leftBox, rightBox;
  for (int k = 0; k < 3; ++k) {
    const glm::vec3& a = v[k];
    const glm::vec3& b = v[(k + 1) % 3];
    if (a[dimension] <= position) leftBox.extend(a);
    if (a[dimension] >= position) rightBox.extend(a);
    if ((a[dimension] < position && b[dimension] > position) || (a[dimension] > position && b[dimension] < position)) {
      const float t = (position - a[dimension]) / (b[dimension] - a[dimension]);
      glm::vec3 crossing = a + t * (b - a);
      crossing[dimension] = position;
      leftBox.extend(crossing);
      rightBox.extend(crossing);
    }
  }
  const Box whole = toBox(RTCBounds{primitive->lower_x, primitive->lower_y, primitive->lower_z, 0, primitive->upper_x,
                                    primitive->upper_y, primitive->upper_z, 0});
  auto clip = [&](Box b, bool isLeft) {
    if (b.empty()) b = whole;  // a reference touching the plane at one point only
    b.min = glm::max(b.min, whole.min);
    b.max = glm::min(b.max, whole.max);
    if (isLeft)
      b.max[dimension] = std::min(b.max[dimension], position);
    else
      b.min[dimension] = std::max(b.min[dimension], position);
    b.max = glm::max(b.max, b.min);
    return RTCBounds{b.min.x, b.min.y, b.min.z, 0, b.max.x, b.max.y, b.max.z, 0};
  };
  *left = clip(leftBox, true);
  *right = clip(rightBox, false);
}

// A compressed node's quantization grid (gpu::BvhCompressedNode): from the node's padded lower corner, in
// steps of a power of two per axis that reach its upper corner in 255 steps. Bounds are rounded outward
// against the decoded value the GPU computes, origin + q x step in float (the product is exact: q has 8
// bits and the step is a power of two), so a decoded child box always holds the padded one.
struct Grid {
  glm::vec3 origin;
  glm::ivec3 exponent;  // step 2^exponent, within float's normal range

  explicit Grid(const Box& node) : origin(node.min) {
    for (int a = 0; a < 3; ++a) {
      const float extent = node.max[a] - node.min[a];
      int e = extent > 0 ? int(std::ceil(std::log2(double(extent) / 255.0))) : -126;
      e = std::clamp(e, -126, 127);
      while (e < 127 && decoded(a, 255, e) < node.max[a]) ++e;
      exponent[a] = e;
    }
  }
  float decoded(int axis, std::uint32_t q, int e) const { return origin[axis] + float(q) * std::ldexp(1.0f, e); }
  std::uint32_t lower(int axis, float value) const {
    const float step = std::ldexp(1.0f, exponent[axis]);
    auto q = std::uint32_t(std::clamp(std::floor(double(value - origin[axis]) / double(step)), 0.0, 255.0));
    while (q > 0 && decoded(axis, q, exponent[axis]) > value) --q;
    return q;
  }
  std::uint32_t upper(int axis, float value) const {
    const float step = std::ldexp(1.0f, exponent[axis]);
    auto q = std::uint32_t(std::clamp(std::ceil(double(value - origin[axis]) / double(step)), 0.0, 255.0));
    while (q < 255 && decoded(axis, q, exponent[axis]) < value) ++q;
    return q;
  }
  std::uint32_t exponents() const {  // biased, a byte per axis
    return std::uint32_t(exponent.x + 127) | std::uint32_t(exponent.y + 127) << 8 |
           std::uint32_t(exponent.z + 127) << 16;
  }
};

// Writes Embree's tree into the GPU layout, depth first, and counts what it wrote.
class Flattener {
 public:
  Flattener(Bvh& bvh, const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices)
      : bvh_(bvh), positions_(positions), indices_(indices) {}

  void binary(const BuildNode* node, size_t index, const Box& bounds, int depth) {
    const Box box = padded(bounds);
    gpu::BvhNode& out = bvh_.nodes[index];
    out.boundsMin = box.min;
    out.boundsMax = box.max;
    note(depth);
    if (node->leaf) {
      const LeafNode& leaf = *static_cast<const LeafNode*>(node);
      out.firstChildOrTriangle = leafTriangles(leaf, box);
      out.triangleCount = leaf.count;
      return;
    }
    const InnerNode& inner = *static_cast<const InnerNode*>(node);
    if (inner.childCount != 2)
      throw std::runtime_error("BVH: Embree made a binary node of " + std::to_string(inner.childCount) + " children");
    const size_t first = bvh_.nodes.size();
    bvh_.nodes.resize(first + 2);
    bvh_.nodes[index].firstChildOrTriangle = std::uint32_t(first);
    bvh_.nodes[index].triangleCount = 0;
    bvh_.stats.sahCost += 2.0 * area(box);
    for (unsigned c = 0; c < 2; ++c) binary(inner.children[c], first + c, toBox(inner.bounds[c]), depth + 1);
  }

  // An inner node's children into wideNodes[index]; a leaf root is the only child of the root.
  void wide(const BuildNode* node, size_t index, const Box& bounds, int depth) {
    const Box nodeBox = padded(bounds);
    note(depth);
    const InnerNode* inner = node->leaf ? nullptr : static_cast<const InnerNode*>(node);
    const unsigned count = inner ? inner->childCount : 1;
    gpu::BvhWideNode out{};
    out.children = glm::uvec4(gpu::kBvhEmptyChild);
    bvh_.stats.sahCost += double(gpu::kBvhWidth) * area(nodeBox);
    for (unsigned c = 0; c < count; ++c) {
      const BuildNode* child = inner ? inner->children[c] : node;
      const Box box = padded(inner ? toBox(inner->bounds[c]) : bounds);
      out.lowerX[int(c)] = box.min.x, out.upperX[int(c)] = box.max.x;
      out.lowerY[int(c)] = box.min.y, out.upperY[int(c)] = box.max.y;
      out.lowerZ[int(c)] = box.min.z, out.upperZ[int(c)] = box.max.z;
      if (child->leaf) {
        const LeafNode& leaf = *static_cast<const LeafNode*>(child);
        note(depth + 1);
        const std::uint32_t first = leafTriangles(leaf, box);
        if (first > gpu::kBvhLeafFirstMask)
          throw std::runtime_error("BVH: more triangle references than 4-wide leaves address");
        out.children[int(c)] = gpu::kBvhLeaf | (leaf.count - 1) << gpu::kBvhLeafCountShift | first;
      } else {
        const size_t childIndex = bvh_.wideNodes.size();
        bvh_.wideNodes.emplace_back();
        out.children[int(c)] = std::uint32_t(childIndex);
        wide(child, childIndex, box, depth + 1);
      }
    }
    bvh_.wideNodes[index] = out;
  }

  // An inner node's children into compressedNodes[index]: inner children at consecutive nodes, leaves'
  // triangles consecutive, boxes quantized outward on the node's grid; a leaf root is the only child.
  void compressed(const BuildNode* node, size_t index, const Box& bounds, int depth) {
    const Box nodeBox = padded(bounds);
    note(depth);
    const InnerNode* inner = node->leaf ? nullptr : static_cast<const InnerNode*>(node);
    const unsigned count = inner ? inner->childCount : 1;
    bvh_.stats.sahCost += double(gpu::kBvhCompressedWidth) * area(nodeBox);
    gpu::BvhCompressedNode out{};
    const Grid grid(nodeBox);
    out.origin = grid.origin;
    out.exponents = grid.exponents();
    out.childBase = std::uint32_t(bvh_.compressedNodes.size());
    out.triangleBase = std::uint32_t(bvh_.triangles.size());
    std::uint32_t meta[gpu::kBvhCompressedWidth], q[6][gpu::kBvhCompressedWidth] = {};
    std::fill(std::begin(meta), std::end(meta), gpu::kBvhMetaEmpty);
    std::vector<std::pair<const BuildNode*, Box>> innerChildren;
    for (unsigned c = 0; c < count; ++c) {
      const BuildNode* child = inner ? inner->children[c] : node;
      const Box childBounds = inner ? toBox(inner->bounds[c]) : bounds, box = padded(childBounds);
      for (int a = 0; a < 3; ++a) {
        q[a][c] = grid.lower(a, box.min[a]);
        q[3 + a][c] = grid.upper(a, box.max[a]);
      }
      if (child->leaf) {
        const LeafNode& leaf = *static_cast<const LeafNode*>(child);
        note(depth + 1);
        const std::uint32_t offset = leafTriangles(leaf, box) - out.triangleBase;
        meta[c] = (leaf.count - 1) << gpu::kBvhMetaCountShift | offset;
      } else {
        meta[c] = gpu::kBvhMetaInner | std::uint32_t(innerChildren.size());
        innerChildren.emplace_back(child, childBounds);
      }
    }
    auto bytes = [](const std::uint32_t* values) {
      glm::uvec2 words(0);
      for (unsigned i = 0; i < gpu::kBvhCompressedWidth; ++i) words[int(i / 4)] |= values[i] << (8 * (i % 4));
      return words;
    };
    out.meta = bytes(meta);
    out.exponents |= ((1u << count) - 1u) << 24;  // the slots in use
    out.lowerXY = glm::uvec4(bytes(q[0]), bytes(q[1]));
    out.lowerZUpperX = glm::uvec4(bytes(q[2]), bytes(q[3]));
    out.upperYZ = glm::uvec4(bytes(q[4]), bytes(q[5]));
    if (out.childBase + innerChildren.size() > gpu::kBvhCompressedNodeMask + 1)
      throw std::runtime_error("BVH: more compressed nodes than the traversal's stack addresses");
    bvh_.compressedNodes.resize(bvh_.compressedNodes.size() + innerChildren.size());
    bvh_.compressedNodes[index] = out;
    for (size_t i = 0; i < innerChildren.size(); ++i)
      compressed(innerChildren[i].first, out.childBase + i, innerChildren[i].second, depth + 1);
  }

  void setRootArea(const Box& root) { rootArea_ = std::max(double(root.area()), 1e-30); }

 private:
  double area(const Box& b) const { return double(b.area()) / rootArea_; }
  void note(int depth) {
    ++bvh_.stats.nodeCount;
    bvh_.stats.maxDepth = std::max(bvh_.stats.maxDepth, depth);
  }
  std::uint32_t leafTriangles(const LeafNode& leaf, const Box& box) {
    const std::uint32_t first = std::uint32_t(bvh_.triangles.size());
    for (unsigned i = 0; i < leaf.count; ++i) {
      const std::uint32_t t = leaf.triangles[i];
      const glm::vec3 v0 = positions_[indices_[3 * size_t(t)]], v1 = positions_[indices_[3 * size_t(t) + 1]],
                      v2 = positions_[indices_[3 * size_t(t) + 2]];
      bvh_.triangles.push_back({v0, t, v1 - v0, 0u, v2 - v0, 0.0f});
    }
    ++bvh_.stats.leafCount;
    bvh_.stats.maxLeafSize = std::max(bvh_.stats.maxLeafSize, size_t(leaf.count));
    bvh_.stats.sahCost += double(leaf.count) * area(box);
    return first;
  }

  Bvh& bvh_;
  const std::vector<glm::vec3>& positions_;
  const std::vector<std::uint32_t>& indices_;
  double rootArea_ = 1;
};

struct DeviceDeleter {
  void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
};
struct BvhDeleter {
  void operator()(RTCBVHTy* b) const { rtcReleaseBVH(b); }
};

// Embree 3 reports an error code only.
std::string embreeError(RTCDevice device) {
  switch (rtcGetDeviceError(device)) {
    case RTC_ERROR_NONE:
      return "no error reported";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

}  // namespace

Bvh buildBvh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices, BvhLayout layout,
             BvhQuality quality) {
  Bvh bvh;
  bvh.layout = layout;
  bvh.quality = quality;
  const size_t count = indices.size() / 3;
  if (count == 0) return bvh;
  if (count > size_t(std::numeric_limits<std::uint32_t>::max()) / 2)
    throw std::runtime_error("BVH: " + std::to_string(count) + " triangles, more than the builder indexes");

  // One reference per triangle, and room for as many again made by spatial splits.
  std::vector<RTCBuildPrimitive> primitives;
  primitives.reserve(2 * count);
  Box root;
  for (size_t t = 0; t < count; ++t) {
    Box b;
    for (int k = 0; k < 3; ++k) b.extend(positions[indices[3 * t + size_t(k)]]);
    root.extend(b.min), root.extend(b.max);
    primitives.push_back({b.min.x, b.min.y, b.min.z, 0u, b.max.x, b.max.y, b.max.z, std::uint32_t(t)});
  }

  std::unique_ptr<RTCDeviceTy, DeviceDeleter> device(rtcNewDevice(nullptr));
  if (!device) throw std::runtime_error("BVH: Embree device: " + embreeError(nullptr));
  std::unique_ptr<RTCBVHTy, BvhDeleter> tree(rtcNewBVH(device.get()));
  BuildContext context{positions, indices, maxLeafSize(layout)};
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = quality == BvhQuality::High     ? RTC_BUILD_QUALITY_HIGH  // SAH with spatial splits
                      : quality == BvhQuality::Medium ? RTC_BUILD_QUALITY_MEDIUM
                                                      : RTC_BUILD_QUALITY_LOW;
  args.maxBranchingFactor = maxWidth(layout);
  args.maxDepth = maxDepth(layout);
  args.sahBlockSize = 1;
  args.minLeafSize = 1;
  args.maxLeafSize = maxLeafSize(layout);
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = tree.get();
  args.primitives = primitives.data();
  args.primitiveCount = primitives.size();
  args.primitiveArrayCapacity = primitives.capacity();
  args.createNode = createNode;
  args.setNodeChildren = setNodeChildren;
  args.setNodeBounds = setNodeBounds;
  args.createLeaf = createLeaf;
  args.splitPrimitive = splitPrimitive;
  args.userPtr = &context;
  const BuildNode* top = static_cast<const BuildNode*>(rtcBuildBVH(&args));
  if (!top) throw std::runtime_error("BVH: Embree's builder failed: " + embreeError(device.get()));
  if (context.oversizedLeaf)
    throw std::runtime_error("BVH: a leaf of more than " + std::to_string(maxLeafSize(layout)) +
                             " triangles at the depth limit (a pile of overlapping triangles?)");

  Flattener flatten(bvh, positions, indices);
  flatten.setRootArea(padded(root));
  bvh.triangles.reserve(primitives.size());
  if (layout == BvhLayout::Wide4) {
    bvh.wideNodes.reserve(primitives.size() / 2 + 1);
    bvh.wideNodes.emplace_back();
    flatten.wide(top, 0, root, 0);
  } else if (layout == BvhLayout::Compressed8) {
    bvh.compressedNodes.reserve(primitives.size() / 4 + 1);
    bvh.compressedNodes.emplace_back();
    flatten.compressed(top, 0, root, 0);
  } else {
    bvh.nodes.reserve(2 * primitives.size());
    bvh.nodes.emplace_back();
    flatten.binary(top, 0, root, 0);
  }
  bvh.stats.triangleReferences = bvh.triangles.size();
  const unsigned depthLimit = maxDepth(layout);
  if (bvh.stats.maxDepth > int(depthLimit))
    throw std::runtime_error("BVH: depth " + std::to_string(bvh.stats.maxDepth) + " is beyond the GPU stack's " +
                             std::to_string(depthLimit));
  return bvh;
}

}  // namespace lgh
