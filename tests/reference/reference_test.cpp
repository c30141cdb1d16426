// The exact CPU reference of the sweep (bench/reference/reference.h: Embree, double precision) against the GL
// code path, on a scene small enough for both: the project's Cornell box at 64x36 with ~1K VPLs.
//  * Unshadowed, it equals the GL brute force (compute sum over every S0 light, and the rasterized
//    RenderSettings::bruteForce light pass) within 1e-4 relative.
//  * Its shadow rays see what the GPU BVH sees: the same rays traced by both agree but for a few edge
//    cases, and the shadowed sums agree with BruteForcePass's shadowed variant.
//  * A pixel subset computes exactly the full reference's values there; the cache returns what was
//    stored, and only for the same description.
//  * In tiles (bench/reference/reference_tiles.h): the tiles cover every pixel once, the reference assembled from
//    tiles (also tiles stored and loaded back) is the one-piece reference bit for bit, and a tile file
//    that is truncated, corrupt, of another reference, tile or pixel subset is refused.
#include "bench/reference/reference.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>

#include "bench/engine/motion_error.h"
#include "bench/reference/reference_tiles.h"
#include "gl_test_env.h"
#include "gltf_writer.h"
#include "lgh/shading.h"
#include "render/exact/brute_force_pass.h"
#include "render/gl/program.h"
#include "render/image_compare.h"
#include "render/passes/lgh_build_pass.h"
#include "render/renderer.h"
#include "render/scene/bvh.h"
#include "render/scene/gpu_bvh.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"
#include "shared/bindings.h"
#include "shared/lgh_types.h"

namespace lgh::test {
namespace {

// The Cornell box rendered once: its G-buffer, S0, and the reference's input.
struct CornellFrame {
  Scene scene;
  SceneGpu gpu;
  RenderSettings settings;
  Renderer renderer;
  reference::ReferenceInput input;

  static RenderSettings small() {
    RenderSettings s;
    s.image.width = 64;
    s.image.height = 36;
    s.inputLights.vpls = 1000;
    s.shadows.samples = 0;
    return s;
  }
  CornellFrame()
      : scene(loadScene(sourceDir() / "data/cornell_box.gltf")),
        gpu(scene),
        settings(small()),
        renderer(gpu, settings) {
    renderer.render(makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height));
    input.width = settings.image.width;
    input.height = settings.image.height;
    input.position = renderer.readImage(Aov::Position).pixels;
    input.normal = renderer.readImage(Aov::Normal).pixels;
    input.lights = fromGpuLights(renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count));
    input.clampDistance = renderer.clampDistance();
  }
  // BruteForcePass on the renderer's G-buffer (shadowed through the GPU BVH when asked).
  ImageRGBA glBruteForce(bool shadowed) const {
    static BruteForcePass pass;
    gl::Texture2D out({"test", "out"}, settings.image.width, settings.image.height, GL_RGBA32F);
    pass.execute(
        {renderer.gbuffer(), renderer.inputLights().lights, renderer.inputLights().count, shadowed ? &gpu : nullptr},
        renderer.clampDistance(), out);
    return fromGLRows(settings.image.width, settings.image.height, out.readRGBA());
  }
};

reference::ReferenceImage computeQuietly(const reference::OcclusionScene& occlusion,
                                         const reference::ReferenceInput& input, double fraction = 1.0) {
  reference::ReferenceOptions o;
  o.pixelFraction = fraction;
  o.progress = false;
  return reference::computeReference(occlusion, input, o);
}

struct Agreement {
  double maxRelative = 0;   // max over pixels and channels of |a - r| / (|r| + 1e-3 mean)
  double relativeRmse = 0;  // luminance, as the sweep measures errors
};

Agreement compare(const ImageRGBA& gl, const reference::ReferenceImage& ref, const std::vector<glm::dvec3>& values) {
  double mean = 0;
  for (const glm::dvec3& v : values) mean += luminance(v);
  mean /= double(std::max<size_t>(values.size(), 1));
  Agreement a;
  double squared = 0, norm = 0;
  for (size_t k = 0; k < ref.pixels.size(); ++k) {
    const glm::vec4& g = gl.pixels[ref.pixels[k]];
    for (int c = 0; c < 3; ++c)
      a.maxRelative =
          std::max(a.maxRelative, std::abs(double(g[c]) - values[k][c]) / (std::abs(values[k][c]) + 1e-3 * mean));
    const double d = luminance(g) - luminance(values[k]);
    squared += d * d;
    norm += luminance(values[k]) * luminance(values[k]);
  }
  a.relativeRmse = std::sqrt(squared / std::max(norm, 1e-300));
  return a;
}

class ReferenceTest : public GLTest {};

TEST_F(ReferenceTest, UnshadowedSumMatchesGlBruteForce) {
  CornellFrame f;
  ASSERT_GT(f.input.lights.size(), 500u);
  const reference::OcclusionScene occlusion(f.scene.positions, f.scene.indices);
  const reference::ReferenceImage ref = computeQuietly(occlusion, f.input);
  ASSERT_TRUE(ref.full());
  double mean = 0;
  for (const glm::dvec3& v : ref.unshadowed) mean += luminance(v);
  ASSERT_GT(mean, 0.0);

  // The compute-shader sum (float, batched) and the rasterized brute force (every light full-screen).
  const Agreement compute = compare(f.glBruteForce(false), ref, ref.unshadowed);
  RenderSettings s = f.settings;
  s.lightPass.bruteForce = true;
  f.renderer.setSettings(s);
  f.renderer.render(makeCameraView(resolveCamera(f.scene, s), s.image.width, s.image.height));
  const Agreement raster = compare(f.renderer.readImage(Aov::Irradiance), ref, ref.unshadowed);
  std::printf(
      "  %zu lights: compute brute force max rel. %.2e, rel. RMSE %.2e; rasterized max rel. %.2e, rel. RMSE %.2e\n",
      f.input.lights.size(), compute.maxRelative, compute.relativeRmse, raster.maxRelative, raster.relativeRmse);
  EXPECT_LT(compute.maxRelative, 1e-4);
  EXPECT_LT(raster.maxRelative, 1e-4);
  EXPECT_LT(compute.relativeRmse, 1e-5);
  EXPECT_LT(raster.relativeRmse, 1e-5);
}

// The same shadow rays (every lit pixel-light pair of the reference) through Embree and through the
// GPU BVH (tests/trace_rays.comp). Embree is watertight, the GPU's Moller-Trumbore is not, so rays
// through a shared edge may differ: allowed for at most 1e-3 of the rays.
TEST_F(ReferenceTest, VisibilityAgreesWithGpuBvh) {
  CornellFrame f;
  const reference::OcclusionScene occlusion(f.scene.positions, f.scene.indices);
  struct TestRay {
    glm::vec4 originTMin, directionTMax;
  };
  struct TestHit {
    float t;
    std::uint32_t sceneTriangle, anyHit, pad;
  };
  std::vector<reference::OcclusionScene::Ray> rays;
  std::vector<TestRay> gpuRays;
  for (size_t i = 0; i < f.input.position.size(); ++i) {
    if (f.input.position[i].w <= 0) continue;
    const glm::vec3 p(f.input.position[i]), n(f.input.normal[i]);
    const glm::dvec3 x(p), nx(n);
    for (const Light& l : f.input.lights) {
      const glm::dvec3 e = lightContribution(glm::dvec3(l.position), glm::dvec3(l.intensity), unitNormal(l),
                                             omniFraction(l), x, &nx, f.input.clampDistance);
      reference::OcclusionScene::Ray ray;
      if (e == glm::dvec3(0.0) || !reference::shadowRay(p, n, l.position, ray)) continue;
      rays.push_back(ray);
      gpuRays.push_back({glm::vec4(ray.origin, ray.tMin), glm::vec4(ray.direction, ray.tMax)});
    }
  }
  ASSERT_GT(rays.size(), 100000u);
  const std::vector<std::uint8_t> cpu = occlusion.occluded(rays);

  // Each BVH layout's answers (the scene's own, and the other built here).
  for (BvhLayout layout : kBvhLayouts) {
    const Bvh bvh = buildBvh(f.scene.positions, f.scene.indices, layout);
    const GpuBvh gpuBvh(bvh);
    gl::Buffer rayBuffer = gl::Buffer::fromVector({"test", "data"}, gpuRays),
               hitBuffer({"test", "hits"}, gpuRays.size() * sizeof(TestHit));
    gpuBvh.bind();
    rayBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
    hitBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
    TracingProgram("tests/trace_rays.comp").forBvh(bvh).dispatch1D(gpuRays.size(), 64);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<TestHit> gpuHits = hitBuffer.downloadAll<TestHit>();

    size_t blocked = 0, differ = 0;
    std::ostringstream name;
    name << layout;
    for (size_t i = 0; i < rays.size(); ++i) {
      blocked += cpu[i];
      differ += (gpuHits[i].anyHit != 0) != (cpu[i] != 0) ? 1 : 0;
    }
    std::printf("  %s BVH: %zu shadow rays, %zu blocked (Embree); %zu differ from the GPU's (%.2e)\n",
                name.str().c_str(), rays.size(), blocked, differ, double(differ) / double(rays.size()));
    EXPECT_GT(blocked, rays.size() / 100) << "the scene should cast some indirect shadows";
    EXPECT_LT(blocked, rays.size() * 99 / 100);
    EXPECT_LE(double(differ), 1e-3 * double(rays.size()));
  }

  // The shadowed sums: Embree's against BruteForcePass's shadowed variant (the same rays on the GPU).
  const reference::ReferenceImage ref = computeQuietly(occlusion, f.input);
  const Agreement shadowed = compare(f.glBruteForce(true), ref, ref.shadowed);
  std::printf("  shadowed sum vs GL shadowed brute force: rel. RMSE %.2e, max rel. %.2e\n", shadowed.relativeRmse,
              shadowed.maxRelative);
  EXPECT_LT(shadowed.relativeRmse, 1e-3);
  double unshadowed = 0, visible = 0;
  for (size_t k = 0; k < ref.pixels.size(); ++k) {
    unshadowed += luminance(ref.unshadowed[k]);
    visible += luminance(ref.shadowed[k]);
  }
  EXPECT_LT(visible, unshadowed);
  EXPECT_GT(visible, 0.1 * unshadowed);
}

TEST_F(ReferenceTest, PixelSubsetMatchesFullReference) {
  CornellFrame f;
  const reference::OcclusionScene occlusion(f.scene.positions, f.scene.indices);
  const reference::ReferenceImage full = computeQuietly(occlusion, f.input);
  const reference::ReferenceImage subset = computeQuietly(occlusion, f.input, 0.25);
  const double n = double(full.pixels.size()), expected = 0.25 * n, sigma = std::sqrt(n * 0.25 * 0.75);
  EXPECT_NEAR(double(subset.pixels.size()), expected, 4 * sigma);
  ASSERT_FALSE(subset.full());
  for (size_t k = 0; k < subset.pixels.size(); ++k) {
    const std::uint32_t i = subset.pixels[k];
    ASSERT_EQ(full.pixels[i], i);
    EXPECT_EQ(subset.unshadowed[k], full.unshadowed[i]);
    EXPECT_EQ(subset.shadowed[k], full.shadowed[i]);
    if (k > 0) {
      EXPECT_LT(subset.pixels[k - 1], i);
    }
  }
  // Another seed, another subset.
  EXPECT_NE(reference::choosePixels(64, 36, 0.25, 1), reference::choosePixels(64, 36, 0.25, 2));
}

TEST(ReferenceTiles, CoverEveryPixelOnce) {
  for (const auto& [w, h, size] : {std::tuple{64, 36, 16}, std::tuple{65, 37, 16}, std::tuple{7, 5, 32},
                                   std::tuple{10, 10, 1}, std::tuple{33, 1, 8}}) {
    const reference::TileGrid grid{w, h, size};
    const std::vector<std::uint32_t> all = reference::choosePixels(w, h, 1.0, 1);
    const std::vector<std::uint32_t> subset = reference::choosePixels(w, h, 0.3, 7);
    for (const std::vector<std::uint32_t>* pixels : {&all, &subset}) {
      std::vector<int> seen(size_t(w) * size_t(h), 0);
      size_t total = 0;
      for (int t = 0; t < grid.count(); ++t) {
        const reference::TileGrid::Rect r = grid.rect(t);
        const std::vector<std::uint32_t> inside = grid.pixelsOf(t, *pixels);
        EXPECT_TRUE(std::is_sorted(inside.begin(), inside.end()));
        for (std::uint32_t p : inside) {
          const int x = int(p) % w, y = int(p) / w;
          EXPECT_TRUE(x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1) << grid.label(t) << " holds pixel " << p;
          ++seen[p];
        }
        total += inside.size();
      }
      EXPECT_EQ(total, pixels->size()) << w << "x" << h << " tiles of " << size;
      for (std::uint32_t p : *pixels) EXPECT_EQ(seen[p], 1) << "pixel " << p;
    }
  }
}

TEST_F(ReferenceTest, TilesAssembleToTheOnePieceReferenceBitForBit) {
  CornellFrame f;
  const reference::OcclusionScene occlusion(f.scene.positions, f.scene.indices);
  reference::ReferenceOptions o;
  o.progress = false;
  for (double fraction : {1.0, 0.4}) {
    o.pixelFraction = fraction;
    const reference::ReferenceImage whole = reference::computeReference(occlusion, f.input, o);
    const reference::TileGrid grid{f.input.width, f.input.height, 16};
    TempDir dir;
    const reference::TileStore store(dir.path(), "cornell test\n", grid);
    std::vector<reference::ReferenceImage> parts;
    for (int t = 0; t < grid.count(); ++t) {
      store.store(t, reference::computePixels(occlusion, f.input, grid.pixelsOf(t, whole.pixels), o));
      std::string why;
      auto part = store.load(t, whole.pixels, &why);
      ASSERT_TRUE(part) << why;
      parts.push_back(std::move(*part));
    }
    const reference::ReferenceImage assembled = reference::assembleTiles(grid, whole.pixels, parts);
    EXPECT_EQ(assembled.pixels, whole.pixels);
    EXPECT_EQ(assembled.unshadowed, whole.unshadowed);  // exact: each pixel's sums are its own
    EXPECT_EQ(assembled.shadowed, whole.shadowed);
    EXPECT_EQ(assembled.rays, whole.rays);
    EXPECT_EQ(assembled.pairs, whole.pairs);
    // Parts that miss a pixel, or hold one twice, are refused.
    std::vector<reference::ReferenceImage> missing = parts;
    missing[1] = missing[0];
    EXPECT_THROW(reference::assembleTiles(grid, whole.pixels, missing), std::invalid_argument);
  }
}

TEST(ReferenceTiles, BadTileFilesAreRefused) {
  TempDir dir;
  const reference::TileGrid grid{8, 4, 4};  // tiles 0 (x 0-3) and 1 (x 4-7)
  const std::vector<std::uint32_t> pixels = reference::choosePixels(8, 4, 1.0, 1);
  reference::ReferenceImage part;
  part.width = 8;
  part.height = 4;
  part.pixels = grid.pixelsOf(1, pixels);
  for (std::uint32_t p : part.pixels) {
    part.unshadowed.push_back(glm::dvec3(p, 2 * p, 0.5));
    part.shadowed.push_back(glm::dvec3(p, p, 0.25));
  }
  part.rays = 7;
  const reference::TileStore store(dir.path(), "key a\n", grid);
  store.store(1, part);
  std::string why;
  ASSERT_TRUE(store.load(1, pixels, &why)) << why;
  EXPECT_EQ(store.load(1, pixels)->shadowed, part.shadowed);
  EXPECT_FALSE(store.load(0, pixels, &why));  // no file: absent, no reason
  EXPECT_TRUE(why.empty());
  // Another key (another folder, and a file copied there), another subset, another tile (a file
  // renamed), another tile size.
  const reference::TileStore other(dir.path(), "key b\n", grid);
  EXPECT_FALSE(other.load(1, pixels));
  std::filesystem::create_directories(other.dir());
  std::filesystem::copy_file(store.file(1), other.file(1));
  EXPECT_FALSE(other.load(1, pixels, &why));
  EXPECT_NE(why.find("another reference"), std::string::npos) << why;
  EXPECT_FALSE(store.load(1, reference::choosePixels(8, 4, 0.5, 3), &why));
  EXPECT_NE(why.find("other pixels"), std::string::npos) << why;
  std::filesystem::copy_file(store.file(1), store.file(0));
  EXPECT_FALSE(store.load(0, pixels, &why));
  EXPECT_NE(why.find("another tile"), std::string::npos) << why;
  EXPECT_FALSE(reference::TileStore(dir.path(), "key a\n", reference::TileGrid{8, 4, 2}).load(1, pixels));
  // One flipped byte anywhere, or a truncation: the checksum catches it.
  const std::filesystem::path file = store.file(1);
  const auto size = std::filesystem::file_size(file);
  for (std::uintmax_t at : {std::uintmax_t(3), size / 2, size - 9, size - 1}) {
    std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
    io.seekg(std::streamoff(at));
    const char c = char(io.get());
    io.seekp(std::streamoff(at));
    io.put(char(c ^ 0x10));
    io.close();
    EXPECT_FALSE(store.load(1, pixels, &why)) << "byte " << at;
    EXPECT_FALSE(why.empty());
    io.open(file, std::ios::in | std::ios::out | std::ios::binary);
    io.seekp(std::streamoff(at));
    io.put(c);
  }
  ASSERT_TRUE(store.load(1, pixels));
  std::filesystem::resize_file(file, size - 20);
  EXPECT_FALSE(store.load(1, pixels, &why));
  EXPECT_NE(why.find("checksum"), std::string::npos) << why;
  store.remove();
  EXPECT_FALSE(std::filesystem::exists(store.dir()));
}

TEST(ReferenceCache, RoundTripAndKeying) {
  TempDir dir;
  reference::ReferenceImage image;
  image.width = 3;
  image.height = 2;
  image.pixels = {0, 2, 5};
  image.unshadowed = {{1, 2, 3}, {4, 5, 6}, {0.1, 0.2, 0.3}};
  image.shadowed = {{1, 1, 1}, {0, 0, 0}, {0.05, 0.1, 0.15}};
  image.seconds = 1.5;
  image.rays = 42;
  image.pairs = 99;
  image.threads = 2;
  image.lightCount = 33;
  reference::storeReference(dir.path(), "scene a\nseed 1\n", image);
  const auto loaded = reference::loadReference(dir.path(), "scene a\nseed 1\n");
  ASSERT_TRUE(loaded);
  EXPECT_EQ(loaded->pixels, image.pixels);
  EXPECT_EQ(loaded->unshadowed, image.unshadowed);
  EXPECT_EQ(loaded->shadowed, image.shadowed);
  EXPECT_EQ(loaded->rays, 42u);
  EXPECT_EQ(loaded->lightCount, 33u);
  EXPECT_FALSE(reference::loadReference(dir.path(), "scene a\nseed 2\n"));
  // A truncated file is a miss, not a crash or a wrong reference.
  const std::filesystem::path file = dir.path() / reference::cacheFileName("scene a\nseed 1\n");
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 5);
  EXPECT_FALSE(reference::loadReference(dir.path(), "scene a\nseed 1\n"));
  // Order-independent light hashing.
  std::vector<Light> lights{{{0, 1, 2}, {1, 1, 1}, {0, 0, 1}}, {{3, 4, 5}, {2, 2, 2}, {0, 0, 0}}};
  const std::uint64_t h = reference::hashLights(lights);
  std::swap(lights[0], lights[1]);
  EXPECT_EQ(reference::hashLights(lights), h);
  lights[0].intensity.x += 1e-3f;
  EXPECT_NE(reference::hashLights(lights), h);
}

// lgh-bench motion's split of a frame's error into the irradiance's and the visibility's parts: they add up
// to the error I V - R at every pixel, and each vanishes where its own factor is the reference's.
TEST(MotionErrorParts, AddUpToTheErrorAndVanishWhereTheirFactorIsExact) {
  const std::vector<double> unshadowed = {2.0, 1.0, 0.0, 4.0}, shadowed = {1.0, 1.0, 0.0, 0.5};
  const std::vector<double> irradiance = {2.5, 0.8, 0.3, 4.0}, visibility = {0.5, 0.7, 1.0, 0.25};
  const bench::ErrorParts parts = bench::errorParts(irradiance, visibility, unshadowed, shadowed);
  for (size_t k = 0; k < shadowed.size(); ++k)
    EXPECT_NEAR(parts.irradiance[k] + parts.visibility[k], irradiance[k] * visibility[k] - shadowed[k], 1e-12) << k;
  EXPECT_DOUBLE_EQ(parts.visibility[0], 0.0);  // V = V_ref = 1/2: the irradiance's alone
  EXPECT_DOUBLE_EQ(parts.irradiance[0], 0.25);
  EXPECT_DOUBLE_EQ(parts.irradiance[3], 0.0);  // I = R_u: the visibility's alone
  EXPECT_DOUBLE_EQ(parts.visibility[3], 0.5);
}

}  // namespace
}  // namespace lgh::test
