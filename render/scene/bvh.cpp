#include "render/scene/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace lgh {
namespace {

constexpr int kBins = 16;
constexpr size_t kMaxLeafSize = 8;
constexpr float kTraversalCost = 1.0f;     // one box test
constexpr float kIntersectionCost = 1.0f;  // one triangle test
// Leaves are forced above this depth; gpu::kBvhStackSize - 4 leaves room for the root and pending pushes.
constexpr int kMaxDepth = int(gpu::kBvhStackSize) - 4;

struct Box {
  glm::vec3 min{std::numeric_limits<float>::max()}, max{-std::numeric_limits<float>::max()};
  void extend(const glm::vec3& p) { min = glm::min(min, p), max = glm::max(max, p); }
  void extend(const Box& b) { min = glm::min(min, b.min), max = glm::max(max, b.max); }
  float area() const {
    if (min.x > max.x) return 0.0f;
    const glm::vec3 e = max - min;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

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

struct BuildTriangle {
  Box bounds;
  glm::vec3 centroid;
};

struct Split {
  int axis = -1;
  float position = 0;
  float cost = std::numeric_limits<float>::max();
};

class Builder {
 public:
  Builder(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices)
      : positions_(positions), indices_(indices) {
    const size_t count = indices.size() / 3;
    tris_.resize(count);
    order_.resize(count);
    std::iota(order_.begin(), order_.end(), 0u);
    for (size_t i = 0; i < count; ++i) {
      for (int k = 0; k < 3; ++k) tris_[i].bounds.extend(positions[indices[3 * i + k]]);
      tris_[i].centroid = 0.5f * (tris_[i].bounds.min + tris_[i].bounds.max);
    }
  }

  Bvh build() {
    Bvh bvh;
    if (tris_.empty()) return bvh;
    bvh.nodes.reserve(2 * tris_.size());
    bvh.nodes.emplace_back();
    buildNode(bvh, 0, 0, tris_.size(), 0);
    // Triangles in leaf order, as vertex + edges.
    bvh.triangles.reserve(order_.size());
    for (std::uint32_t t : order_) {
      const glm::vec3 v0 = positions_[indices_[3 * t]], v1 = positions_[indices_[3 * t + 1]],
                      v2 = positions_[indices_[3 * t + 2]];
      bvh.triangles.push_back({v0, t, v1 - v0, 0u, v2 - v0, 0.0f});
    }
    bvh.stats.nodeCount = bvh.nodes.size();
    const float rootArea = std::max(Box{bvh.nodes[0].boundsMin, bvh.nodes[0].boundsMax}.area(), 1e-30f);
    for (const gpu::BvhNode& n : bvh.nodes) {
      const float p = Box{n.boundsMin, n.boundsMax}.area() / rootArea;
      bvh.stats.sahCost += n.triangleCount ? p * kIntersectionCost * float(n.triangleCount) : p * 2 * kTraversalCost;
    }
    return bvh;
  }

 private:
  Box rangeBounds(size_t begin, size_t end, bool centroids) const {
    Box b;
    for (size_t i = begin; i < end; ++i) {
      if (centroids)
        b.extend(tris_[order_[i]].centroid);
      else
        b.extend(tris_[order_[i]].bounds);
    }
    return b;
  }

  // Binned SAH over the centroid bounds of the range, all three axes.
  Split findSplit(size_t begin, size_t end, const Box& centroidBounds) const {
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centroidBounds.min[axis], hi = centroidBounds.max[axis];
      if (!(hi > lo)) continue;
      std::array<Box, kBins> binBounds;
      std::array<size_t, kBins> binCounts{};
      const float scale = kBins / (hi - lo);
      for (size_t i = begin; i < end; ++i) {
        const BuildTriangle& t = tris_[order_[i]];
        const int bin = std::min(kBins - 1, int((t.centroid[axis] - lo) * scale));
        binBounds[bin].extend(t.bounds);
        ++binCounts[bin];
      }
      // Sweep from the right to get suffix areas, then from the left to evaluate each plane.
      std::array<float, kBins> rightArea{};
      std::array<size_t, kBins> rightCount{};
      Box acc;
      size_t count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(binBounds[b]);
        count += binCounts[b];
        rightArea[b] = acc.area();
        rightCount[b] = count;
      }
      acc = Box{};
      count = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.extend(binBounds[b]);
        count += binCounts[b];
        if (count == 0 || rightCount[b + 1] == 0) continue;
        const float cost = acc.area() * float(count) + rightArea[b + 1] * float(rightCount[b + 1]);
        if (cost < best.cost) best = {axis, lo + float(b + 1) / scale, cost};
      }
    }
    return best;
  }

  void makeLeaf(Bvh& bvh, size_t nodeIndex, size_t begin, size_t end) {
    bvh.nodes[nodeIndex].firstChildOrTriangle = std::uint32_t(begin);
    bvh.nodes[nodeIndex].triangleCount = std::uint32_t(end - begin);
    ++bvh.stats.leafCount;
    bvh.stats.maxLeafSize = std::max(bvh.stats.maxLeafSize, end - begin);
  }

  void buildNode(Bvh& bvh, size_t nodeIndex, size_t begin, size_t end, int depth) {
    const Box bounds = padded(rangeBounds(begin, end, false));
    bvh.nodes[nodeIndex].boundsMin = bounds.min;
    bvh.nodes[nodeIndex].boundsMax = bounds.max;
    bvh.stats.maxDepth = std::max(bvh.stats.maxDepth, depth);
    const size_t count = end - begin;
    if (count <= 1 || depth >= kMaxDepth) return makeLeaf(bvh, nodeIndex, begin, end);

    const Box centroidBounds = rangeBounds(begin, end, true);
    const Split split = findSplit(begin, end, centroidBounds);
    size_t mid = begin;
    if (split.axis >= 0) {
      // SAH: splitting pays if two child traversals plus their triangles cost less than testing all here.
      const float leafCost = kIntersectionCost * float(count);
      const float splitCost = kTraversalCost + kIntersectionCost * split.cost / std::max(bounds.area(), 1e-30f);
      if (splitCost >= leafCost && count <= kMaxLeafSize) return makeLeaf(bvh, nodeIndex, begin, end);
      mid = size_t(std::partition(order_.begin() + begin, order_.begin() + end,
                                  [&](std::uint32_t t) { return tris_[t].centroid[split.axis] < split.position; }) -
                   order_.begin());
    }
    if (mid == begin || mid == end) {
      // All centroids coincide (or binning could not separate them): split the range in half so
      // that a pile of identical triangles still gets a balanced tree of small leaves.
      if (count <= kMaxLeafSize) return makeLeaf(bvh, nodeIndex, begin, end);
      mid = begin + count / 2;
    }
    const size_t left = bvh.nodes.size();
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    bvh.nodes[nodeIndex].firstChildOrTriangle = std::uint32_t(left);
    bvh.nodes[nodeIndex].triangleCount = 0;
    buildNode(bvh, left, begin, mid, depth + 1);
    buildNode(bvh, left + 1, mid, end, depth + 1);
  }

  const std::vector<glm::vec3>& positions_;
  const std::vector<std::uint32_t>& indices_;
  std::vector<BuildTriangle> tris_;
  std::vector<std::uint32_t> order_;
};

}  // namespace

Bvh buildBvh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  return Builder(positions, indices).build();
}

}  // namespace lgh
