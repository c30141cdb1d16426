// BVH, in each node layout (binary, 4-wide; built by Embree's builder): structure invariants on the CPU,
// and the GPU traversal against brute-force intersection of every triangle (the same shared
// Moller-Trumbore code) on random rays: a triangle soup with flat boxes and a degenerate triangle, the
// same soup 1e6 from the origin, Sponza, one triangle, and a pile of coincident triangles.
//
// Tolerance, documented: results may differ only where float rounding decides the outcome, i.e.
// when a ray passes within kEdgeEpsilon (barycentric) of a triangle edge, or two triangles are hit
// at distances equal within kTieEpsilon (relative). The GLSL compiler may fuse multiply-adds that
// the C++ compiler does not, so exact edge cases can fall either way, and the same triangle's hit
// distance may differ in the last bits (kSameTriangleTEpsilon, relative). Any other difference fails.
#include "render/scene/bvh.h"

#include <algorithm>
#include <functional>
#include <random>
#include <thread>
#include <tuple>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/scene/gpu_bvh.h"
#include "render/scene/scene.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"
#include "render/settings.h"
#include "shared/bindings.h"
#include "shared/ray_triangle.h"
#include "tests/test_types.h"

namespace lgh::test {
namespace {

constexpr float kEdgeEpsilon = 1e-4f;
constexpr float kTieEpsilon = 1e-4f;
constexpr float kSameTriangleTEpsilon = 1e-5f;

using gpu::TestHit;
using gpu::TestRay;

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

Mesh randomSoup(size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(0.01f, 0.2f);
  Mesh mesh;
  for (size_t i = 0; i < count; ++i) {
    const glm::vec3 c(u(rng), u(rng), u(rng));
    const float size = s(rng);
    for (int k = 0; k < 3; ++k) {
      mesh.positions.push_back(c + size * glm::vec3(u(rng), u(rng), u(rng)));
      mesh.indices.push_back(std::uint32_t(mesh.positions.size() - 1));
    }
  }
  // Axis-aligned quads (flat boxes) and a degenerate triangle, which real scenes are full of.
  for (int q = 0; q < 20; ++q) {
    const float y = u(rng);
    const std::uint32_t base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(),
                          {{-0.5f, y, -0.5f}, {0.5f, y, -0.5f}, {0.5f, y, 0.5f}, {-0.5f, y, 0.5f}});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  mesh.positions.insert(mesh.positions.end(), {{0, 0, 0}, {0, 0, 0}, {1, 1, 1}});
  const std::uint32_t d = std::uint32_t(mesh.positions.size() - 3);
  mesh.indices.insert(mesh.indices.end(), {d, d + 1, d + 2});
  return mesh;
}

struct BruteForceHit {
  float t = -1.0f;
  std::uint32_t triangle = 0xffffffffu;
  bool nearEdge = false;  // the closest hit (or a near miss at similar t) is within rounding of an edge
  bool tie = false;       // another triangle is hit at nearly the same distance
};

BruteForceHit bruteForce(const Mesh& mesh, const TestRay& ray) {
  BruteForceHit best;
  const glm::vec3 o(ray.originTMin), d(ray.directionTMax);
  const float tMin = ray.originTMin.w, tMax = ray.directionTMax.w;
  float bestT = tMax;
  for (size_t i = 0; i < mesh.indices.size() / 3; ++i) {
    const glm::vec3 v0 = mesh.positions[mesh.indices[3 * i]];
    const glm::vec3 e1 = mesh.positions[mesh.indices[3 * i + 1]] - v0,
                    e2 = mesh.positions[mesh.indices[3 * i + 2]] - v0;
    // A slightly grown triangle tells whether rounding could flip this triangle's outcome.
    glm::vec3 hit;
    const glm::vec3 grow = kEdgeEpsilon * (e1 + e2);
    const bool hitGrown =
        gpu::intersectTriangle(o, d, v0 - grow, e1 * (1 + 3 * kEdgeEpsilon), e2 * (1 + 3 * kEdgeEpsilon),
                               tMin * (1 - kTieEpsilon), tMax * (1 + kTieEpsilon), hit);
    if (!hitGrown) continue;
    const float tGrown = hit.x;
    const bool hitExact = gpu::intersectTriangle(o, d, v0, e1, e2, tMin, tMax, hit);
    const bool edge = !hitExact || hit.y < kEdgeEpsilon || hit.z < kEdgeEpsilon || hit.y + hit.z > 1 - kEdgeEpsilon;
    const float t = hitExact ? hit.x : tGrown;
    if (std::abs(t - bestT) <= kTieEpsilon * std::max(bestT, 1e-3f)) best.tie = true;
    if (edge && t <= bestT * (1 + kTieEpsilon)) best.nearEdge = true;
    if (hitExact && hit.x < bestT) {
      if (std::abs(hit.x - bestT) > kTieEpsilon * std::max(bestT, 1e-3f)) best.tie = false;
      bestT = hit.x;
      best.t = hit.x;
      best.triangle = std::uint32_t(i);
    }
  }
  return best;
}

// Traces the rays (closest hit and any hit) through `bvh`, which is bound.
std::vector<TestHit> traceBound(const Bvh& bvh, const std::vector<TestRay>& rays) {
  gl::Buffer rayBuffer = gl::Buffer::fromVector({"test", "data"}, rays),
             hitBuffer({"test", "hits"}, rays.size() * sizeof(TestHit));
  rayBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  hitBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  TracingProgram("tests/trace_rays.comp").forBvh(bvh).dispatch1D(rays.size(), 64);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return hitBuffer.downloadAll<TestHit>();
}

std::vector<TestHit> traceOnGpu(const Bvh& bvh, const std::vector<TestRay>& rays) {
  const GpuBvh gpuBvh(bvh);
  gpuBvh.bind();
  return traceBound(bvh, rays);
}

// Compares GPU results with brute force; returns the number of unexplained mismatches.
size_t compareWithBruteForce(const Mesh& mesh, const Bvh& bvh, const std::vector<TestRay>& rays, size_t* excused) {
  const std::vector<TestHit> gpuHits = traceOnGpu(bvh, rays);
  std::vector<BruteForceHit> cpu(rays.size());
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < threads; ++w)
    pool.emplace_back([&, w] {
      for (size_t i = w; i < rays.size(); i += threads) cpu[i] = bruteForce(mesh, rays[i]);
    });
  for (auto& t : pool) t.join();

  size_t mismatches = 0;
  *excused = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const TestHit& g = gpuHits[i];
    const BruteForceHit& c = cpu[i];
    const bool sameHitState = (g.sceneTriangle != 0xffffffffu) == (c.triangle != 0xffffffffu);
    const bool anyConsistent = (g.anyHit != 0) == (c.triangle != 0xffffffffu);
    const bool same = sameHitState && anyConsistent && g.sceneTriangle == c.triangle &&
                      (c.t < 0 || std::abs(g.t - c.t) <= kSameTriangleTEpsilon * c.t);
    if (same) continue;
    const bool sameT = c.t >= 0 && g.t >= 0 && std::abs(g.t - c.t) <= kTieEpsilon * std::max(c.t, 1e-3f);
    if (c.nearEdge || (c.tie && sameT)) {
      ++*excused;
      continue;
    }
    if (++mismatches <= 5)
      ADD_FAILURE() << "ray " << i << ": GPU triangle " << g.sceneTriangle << " t=" << g.t << " any=" << g.anyHit
                    << ", brute force triangle " << c.triangle << " t=" << c.t;
  }
  return mismatches;
}

std::vector<TestRay> randomRays(const glm::vec3& lo, const glm::vec3& hi, size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> n;
  std::vector<TestRay> rays;
  for (size_t i = 0; i < count; ++i) {
    const glm::vec3 o = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 d(n(rng), n(rng), n(rng));
    if (i % 10 == 0) d = glm::vec3(0, i % 20 == 0 ? -1 : 1, 0);  // axis-aligned rays: zero direction components
    d = glm::normalize(d);
    // Mix of unbounded rays and short segments (shadow-ray style).
    const float tMax = (i % 3 == 0) ? glm::length(hi - lo) * u(rng) : std::numeric_limits<float>::infinity();
    rays.push_back({glm::vec4(o, 0.0f), glm::vec4(d, tMax)});
  }
  return rays;
}

// The layouts' children, as boxes and leaf ranges, whatever the node format.
struct Child {
  glm::vec3 lower, upper;
  bool leaf = false;
  std::uint32_t index = 0, count = 0;  // inner: the node; leaf: the first triangle and the count
};

std::vector<Child> childrenOf(const Bvh& bvh, std::uint32_t node) {
  std::vector<Child> out;
  if (bvh.layout == BvhLayout::Binary) {
    const gpu::BvhNode& n = bvh.nodes[node];
    for (std::uint32_t c = 0; c < 2; ++c) {
      const gpu::BvhNode& child = bvh.nodes[n.firstChildOrTriangle + c];
      out.push_back({child.boundsMin, child.boundsMax, child.triangleCount > 0,
                     child.triangleCount > 0 ? child.firstChildOrTriangle : n.firstChildOrTriangle + c,
                     child.triangleCount});
    }
    return out;
  }
  if (bvh.layout == BvhLayout::Compressed8) {
    // The boxes as the traversal decodes them: origin + q x 2^(e - 127), in float.
    const gpu::BvhCompressedNode& n = bvh.compressedNodes[node];
    const glm::uvec4 words[3] = {n.lowerXY, n.lowerZUpperX, n.upperYZ};
    auto byte = [](std::uint32_t word, unsigned c) { return (word >> (8 * (c % 4))) & 0xffu; };
    auto decoded = [&](int bound, unsigned c) {  // bound 0-5: lower x, y, z, upper x, y, z
      const int axis = bound % 3;
      const float step = std::ldexp(1.0f, int((n.exponents >> (8 * axis)) & 0xffu) - 127);
      return n.origin[axis] + float(byte(words[bound / 2][int(2 * (bound % 2) + c / 4)], c)) * step;
    };
    for (unsigned c = 0; c < gpu::kBvhCompressedWidth; ++c) {
      const std::uint32_t meta = byte(n.meta[int(c / 4)], c);
      if (meta == gpu::kBvhMetaEmpty) continue;
      Child child{{decoded(0, c), decoded(1, c), decoded(2, c)}, {decoded(3, c), decoded(4, c), decoded(5, c)}};
      child.leaf = (meta & gpu::kBvhMetaInner) == 0;
      child.index = child.leaf ? n.triangleBase + (meta & gpu::kBvhMetaOffsetMask)
                               : n.childBase + (meta & gpu::kBvhMetaInnerIndexMask);
      child.count = child.leaf ? (meta >> gpu::kBvhMetaCountShift) + 1 : 0;
      out.push_back(child);
    }
    return out;
  }
  const gpu::BvhWideNode& n = bvh.wideNodes[node];
  for (int c = 0; c < 4; ++c) {
    const std::uint32_t ref = n.children[c];
    if (ref == gpu::kBvhEmptyChild) continue;
    Child child{{n.lowerX[c], n.lowerY[c], n.lowerZ[c]}, {n.upperX[c], n.upperY[c], n.upperZ[c]}};
    child.leaf = (ref & gpu::kBvhLeaf) != 0;
    child.index = child.leaf ? ref & gpu::kBvhLeafFirstMask : ref;
    child.count = child.leaf ? ((ref >> gpu::kBvhLeafCountShift) & gpu::kBvhLeafCountMask) + 1 : 0;
    out.push_back(child);
  }
  return out;
}

// Every layout at every build quality (High at a scene's load, kFollowBvhQuality when meshes move).
class BvhBuild : public ::testing::TestWithParam<std::tuple<BvhLayout, BvhQuality>> {
 protected:
  static BvhLayout layout() { return std::get<0>(GetParam()); }
  static Bvh build(const Mesh& mesh) {
    return buildBvh(mesh.positions, mesh.indices, layout(), std::get<1>(GetParam()));
  }
};

// Every scene triangle is in a leaf (more than once only where a spatial split cut it), the triangles a
// leaf alone references lie in its box and in every box above it (what lets the traversal skip a box),
// every box holds its children's (binary, 4-wide: float boxes; a compressed child's box is rounded out on
// its parent's grid and may pass its parent's by a step), and the depth fits the stack.
TEST_P(BvhBuild, StructureInvariants) {
  const Mesh mesh = randomSoup(5000, 1);
  const Bvh bvh = build(mesh);
  const size_t triangleCount = mesh.indices.size() / 3;
  ASSERT_GE(bvh.triangles.size(), triangleCount);
  EXPECT_EQ(bvh.stats.triangleReferences, bvh.triangles.size());
  EXPECT_LT(bvh.stats.maxDepth, int(gpu::kBvhStackSize) - 1);
  EXPECT_LE(bvh.stats.maxLeafSize, layout() == BvhLayout::Compressed8 ? gpu::kBvhCompressedMaxLeafSize : 8u);

  std::vector<int> seen(triangleCount, 0);
  struct Leaf {
    Child leaf;
    std::vector<Child> above;  // the boxes from the root's children down to the leaf's parent
  };
  std::vector<Leaf> leaves;
  size_t visitedLeafTriangles = 0;
  auto inside = [](const Child& box, const glm::vec3& p) {
    return glm::all(glm::greaterThanEqual(p, box.lower)) && glm::all(glm::lessThanEqual(p, box.upper));
  };
  if (layout() == BvhLayout::Binary) {
    ASSERT_EQ(bvh.nodes[0].triangleCount, 0u) << "a root leaf: too few triangles";
  }
  std::vector<Child> above;
  std::function<void(std::uint32_t)> visit = [&](std::uint32_t node) {
    for (const Child& child : childrenOf(bvh, node)) {
      if (!above.empty() && layout() != BvhLayout::Compressed8) {
        ASSERT_TRUE(inside(above.back(), child.lower) && inside(above.back(), child.upper));
      }
      if (!child.leaf) {
        above.push_back(child);
        visit(child.index);
        above.pop_back();
        continue;
      }
      for (std::uint32_t i = 0; i < child.count; ++i) {
        ++seen[bvh.triangles[child.index + i].sceneTriangle];
        ++visitedLeafTriangles;
      }
      leaves.push_back({child, above});
    }
  };
  visit(0);
  EXPECT_EQ(visitedLeafTriangles, bvh.triangles.size());
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s >= 1; }));
  for (const Leaf& leaf : leaves)
    for (std::uint32_t i = 0; i < leaf.leaf.count; ++i) {
      const gpu::BvhTriangle& t = bvh.triangles[leaf.leaf.index + i];
      if (seen[t.sceneTriangle] != 1) continue;
      for (const glm::vec3& p : {t.v0, t.v0 + t.edge1, t.v0 + t.edge2}) {
        ASSERT_TRUE(inside(leaf.leaf, p));
        for (const Child& box : leaf.above) ASSERT_TRUE(inside(box, p));
      }
    }
}

TEST_P(BvhBuild, IdenticalTrianglesStayShallow) {
  // 10,000 copies of one triangle: no split plane separates them; the builder must still terminate
  // with a bounded depth and small leaves.
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int i = 0; i < 10000; ++i) mesh.indices.insert(mesh.indices.end(), {0, 1, 2});
  const Bvh bvh = build(mesh);
  EXPECT_LT(bvh.stats.maxDepth, int(gpu::kBvhStackSize) - 1);
  EXPECT_LE(bvh.stats.maxLeafSize, layout() == BvhLayout::Compressed8 ? gpu::kBvhCompressedMaxLeafSize : 8u);
}

TEST_P(BvhBuild, EmptyAndSingle) {
  const Bvh none = build({});
  EXPECT_TRUE(none.nodes.empty() && none.wideNodes.empty() && none.compressedNodes.empty());
  const Bvh one = build({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}});
  ASSERT_EQ(one.triangles.size(), 1u);
  if (layout() == BvhLayout::Binary) {
    ASSERT_EQ(one.nodes.size(), 1u);
    EXPECT_EQ(one.nodes[0].triangleCount, 1u);
  } else {
    ASSERT_EQ(layout() == BvhLayout::Wide4 ? one.wideNodes.size() : one.compressedNodes.size(), 1u);
    const std::vector<Child> children = childrenOf(one, 0);
    ASSERT_EQ(children.size(), 1u);
    EXPECT_TRUE(children[0].leaf);
    EXPECT_EQ(children[0].count, 1u);
  }
}

const auto kLayouts = ::testing::ValuesIn(kBvhLayouts);
auto layoutName = [](const ::testing::TestParamInfo<BvhLayout>& info) {
  const char* names[] = {"Binary", "Wide4", "Compressed8"};
  return std::string(names[size_t(info.param)]);
};
auto layoutAndQualityName = [](const ::testing::TestParamInfo<std::tuple<BvhLayout, BvhQuality>>& info) {
  const char* qualities[] = {"High", "Medium", "Low"};
  return layoutName(::testing::TestParamInfo<BvhLayout>(std::get<0>(info.param), info.index)) +
         qualities[size_t(std::get<1>(info.param))];
};
INSTANTIATE_TEST_SUITE_P(Layouts, BvhBuild,
                         ::testing::Combine(kLayouts,
                                            ::testing::Values(BvhQuality::High, BvhQuality::Medium, BvhQuality::Low)),
                         layoutAndQualityName);

class BvhTraceTest : public GLTest, public ::testing::WithParamInterface<BvhLayout> {};

TEST_P(BvhTraceTest, MatchesBruteForceOnTriangleSoup) {
  const Mesh mesh = randomSoup(3000, 7);
  const Bvh bvh = buildBvh(mesh.positions, mesh.indices, GetParam());
  const auto rays = randomRays(glm::vec3(-1.2f), glm::vec3(1.2f), 4000, 11);
  size_t excused = 0;
  EXPECT_EQ(compareWithBruteForce(mesh, bvh, rays, &excused), 0u);
  EXPECT_LT(excused, rays.size() / 100) << "too many rays excused as edge cases";
  RecordProperty("excused", int(excused));
}

// The faster builds that follow moving meshes (kFollowBvhQuality, and Embree's fastest) answer as the
// load's does.
TEST_P(BvhTraceTest, MatchesBruteForceAtFasterBuildQualities) {
  const Mesh mesh = randomSoup(3000, 7);
  const auto rays = randomRays(glm::vec3(-1.2f), glm::vec3(1.2f), 4000, 11);
  for (BvhQuality quality : {BvhQuality::Medium, BvhQuality::Low}) {
    SCOPED_TRACE(choiceName(quality, kBvhQualityChoices));
    const Bvh bvh = buildBvh(mesh.positions, mesh.indices, GetParam(), quality);
    size_t excused = 0;
    EXPECT_EQ(compareWithBruteForce(mesh, bvh, rays, &excused), 0u);
    EXPECT_LT(excused, rays.size() / 100) << "too many rays excused as edge cases";
  }
}

// The soup 1e6 from the origin (float spacing 0.06 there): boxes, slabs and triangles at that scale.
TEST_P(BvhTraceTest, MatchesBruteForceFarFromTheOrigin) {
  Mesh mesh = randomSoup(3000, 7);
  const glm::vec3 offset(1e6f, -1e6f, 1e6f);
  for (glm::vec3& p : mesh.positions) p = offset + 100.0f * p;
  const Bvh bvh = buildBvh(mesh.positions, mesh.indices, GetParam());
  const auto rays = randomRays(offset - glm::vec3(120.0f), offset + glm::vec3(120.0f), 4000, 13);
  size_t excused = 0;
  EXPECT_EQ(compareWithBruteForce(mesh, bvh, rays, &excused), 0u);
  EXPECT_LT(excused, rays.size() / 100);
  std::printf("[ BVH      ] 1e6 from the origin: %zu rays, %zu excused as edge/tie cases\n", rays.size(), excused);
}

// No triangle (the GPU's buffers are stubs: every ray misses), one triangle (the root's only leaf), and
// 500 coincident copies of one triangle (no split separates them): the hits are the brute force's (among
// the copies, one at the same distance).
TEST_P(BvhTraceTest, MatchesBruteForceOnNoneOneAndCoincidentTriangles) {
  for (int copies : {0, 1, 500}) {
    Mesh mesh;
    mesh.positions = {{-1, 0, -1}, {1, 0, -1}, {0, 0, 1}};
    for (int i = 0; i < copies; ++i) mesh.indices.insert(mesh.indices.end(), {0, 1, 2});
    const Bvh bvh = buildBvh(mesh.positions, mesh.indices, GetParam());
    const auto rays = randomRays(glm::vec3(-1.5f), glm::vec3(1.5f), 2000, 17);
    size_t excused = 0;
    EXPECT_EQ(compareWithBruteForce(mesh, bvh, rays, &excused), 0u) << copies << " triangles";
    // Among coincident copies every hit is a tie (any copy at the same t is right): only one triangle's
    // edge cases are bounded.
    if (copies == 1) {
      EXPECT_LT(excused, rays.size() / 100);
    }
  }
}

TEST_P(BvhTraceTest, MatchesBruteForceOnSponza) {
  LGH_REQUIRE_SHARED_SCENE(path, "sponza_sun/sponza_sun.gltf");
  const Scene scene = loadScene(path);
  const Mesh mesh{scene.positions, scene.indices};
  const Bvh bvh = buildBvh(mesh.positions, mesh.indices, GetParam());
  const auto rays = randomRays(scene.bounds.min, scene.bounds.max, 3000, 3);
  size_t excused = 0;
  EXPECT_EQ(compareWithBruteForce(mesh, bvh, rays, &excused), 0u);
  EXPECT_LT(excused, rays.size() / 100);
  std::printf(
      "[ BVH      ] sponza: %zu triangles (%zu references), %zu nodes, depth %d, %zu rays, %zu excused as edge/tie "
      "cases\n",
      scene.triangleCount(), bvh.stats.triangleReferences, bvh.stats.nodeCount, bvh.stats.maxDepth, rays.size(),
      excused);
}

// Eight stacked layers of alpha-masked materials (4 x 4 squares each), each layer's texture a row of
// texels kept or cut out at random, with a different width per layer: rays up and down through the stack, some of them
// segments ending inside it, stop at the first layer whose texel there is kept. The traversal stops its walk at each
// masked hit and tests the cut-out outside it, then resumes with the leaf's next triangle, so a walk that resumed
// wrongly skips or repeats them.
TEST_P(BvhTraceTest, StopsAtTheFirstAlphaMaskedLayerThatIsNotCutOut) {
  constexpr int kLayers = 8;
  constexpr std::uint32_t kCells = 4;
  // 1 cm apart, about the origin (which the loader keeps): too close for the build to split them, so each
  // leaf holds triangles of several layers.
  const auto layerY = [](int l) { return 0.01f * (float(l) - 3.5f); };
  const int widths[kLayers] = {3, 5, 7, 4, 6, 9, 2, 8};
  std::mt19937 rng(5);
  std::vector<std::vector<bool>> kept(kLayers);
  TempDir dir;
  GltfWriter w;
  std::vector<PrimitiveDesc> layers;
  for (int l = 0; l < kLayers; ++l) {
    std::vector<std::uint8_t> rgba;
    for (int x = 0; x < widths[l]; ++x) {
      kept[l].push_back(rng() % 5 == 0);
      rgba.insert(rgba.end(), {255, 255, 255, std::uint8_t(kept[l].back() ? 255 : 0)});
    }
    const int texture = w.addTexture(w.addImageEmbedded(encodePng(widths[l], 1, rgba)));
    const int material = w.addMaterial(MaterialDesc{}.withBaseColorTexture(texture).withAlphaMask(0.5));
    PrimitiveDesc layer;  // x, z in [-1, 1] as kCells x kCells squares, texture u = (x + 1) / 2
    layer.material = material;
    for (std::uint32_t j = 0; j <= kCells; ++j)
      for (std::uint32_t i = 0; i <= kCells; ++i) {
        const glm::vec2 uv(float(i) / kCells, float(j) / kCells);
        layer.positions.push_back({2.0f * uv.x - 1.0f, layerY(l), 1.0f - 2.0f * uv.y});
        layer.texcoords.push_back(uv);
      }
    for (std::uint32_t j = 0; j < kCells; ++j)
      for (std::uint32_t i = 0; i < kCells; ++i) {
        const std::uint32_t a = j * (kCells + 1) + i, c = a + kCells + 2;
        layer.indices.insert(layer.indices.end(), {a, a + 1, c, a, c, c - 1});
      }
    layers.push_back(layer);
  }
  w.addNode(NodeDesc{}.withMesh(w.addMesh(layers)));
  const Scene scene = loadScene(w.write(dir / "layers.gltf"));
  ASSERT_EQ(scene.origin, glm::dvec3(0.0));
  const SceneGpu sceneGpu(scene, GetParam());

  // Rays kept clear of texel borders and of the squares' edges and diagonals, where rounding decides.
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<TestRay> rays;
  std::vector<float> expected;  // the closest hit's t, or -1
  while (rays.size() < 4000) {
    const bool up = rays.size() % 2 == 0;
    const glm::vec3 o(u(rng) - 0.5f, up ? -1.0f : 1.0f, u(rng) - 0.5f);
    const glm::vec3 d = glm::normalize(glm::vec3(0.1f * u(rng) - 0.05f, up ? 1.0f : -1.0f, 0.1f * u(rng) - 0.05f));
    const float tMax = rays.size() % 3 == 0 ? 0.96f + 0.08f * u(rng) : std::numeric_limits<float>::infinity();
    float closest = -1.0f;
    bool clear = true;
    for (int k = 0; k < kLayers; ++k) {
      const int l = up ? k : kLayers - 1 - k;
      const float t = (layerY(l) - o.y) / d.y;
      const glm::vec3 p = o + t * d;
      const float texel = (p.x + 1.0f) / 2.0f * float(widths[l]);
      const glm::vec2 cell = glm::fract(glm::vec2(p.x + 1.0f, 1.0f - p.z) / 2.0f * float(kCells));
      const auto away = [](float a) { return std::abs(a - std::round(a)) > 1e-3f; };
      clear =
          clear && away(texel) && away(cell.x) && away(cell.y) && away(cell.x - cell.y) && std::abs(t - tMax) > 1e-4f;
      if (closest < 0.0f && t < tMax && kept[l][size_t(texel)]) closest = t;
    }
    if (!clear) continue;
    rays.push_back({glm::vec4(o, 0.0f), glm::vec4(d, tMax)});
    expected.push_back(closest);
  }
  sceneGpu.bindForCompute();
  ASSERT_TRUE(sceneGpu.bvh().alphaMasked);
  const std::vector<TestHit> hits = traceBound(sceneGpu.bvh(), rays);
  size_t wrong = 0, blocked = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool expectHit = expected[i] >= 0.0f;
    blocked += expectHit;
    const bool right = (hits[i].anyHit != 0) == expectHit &&
                       (expectHit ? std::abs(hits[i].t - expected[i]) < 1e-4f : hits[i].t < 0.0f);
    if (!right && ++wrong <= 5)
      ADD_FAILURE() << "ray " << i << ": closest t " << hits[i].t << ", any hit " << hits[i].anyHit << "; expected t "
                    << expected[i];
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(blocked, rays.size() / 4) << "test set-up: most rays should meet a kept texel";
  EXPECT_LT(blocked, rays.size() * 19 / 20) << "test set-up: some rays should pass every layer or end first";
}

INSTANTIATE_TEST_SUITE_P(Layouts, BvhTraceTest, kLayouts, layoutName);

}  // namespace
}  // namespace lgh::test
