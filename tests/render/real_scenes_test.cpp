// Real-world scenes (issue 14), rendered: scenes far from the origin and extreme clip planes give the
// image the same scene gives at the origin with ordinary clip planes; alphaMode MASK cuts out the
// surface for the camera, the shadow rays and the VPL paths; doubleSided, COLOR_0, TEXCOORD_1,
// KHR_texture_transform and KHR_mesh_quantization change the image as glTF defines. Scenes are
// written by the test (gltf_writer.h); properties are checked per pixel through the G-buffer AOVs.
#include <cstdio>
#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <limits>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "render/image_compare.h"
#include "render/renderer.h"
#include "render/scene/added_lights.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Frame {
  ImageRGBA final, direct, indirect, albedo, position, normal;
  FrameStats stats;
};

RenderSettings testSettings() {
  RenderSettings s;
  s.image.width = 160;
  s.image.height = 90;
  s.inputLights.vpls = 4000;
  s.inputLights.bounces = 1;
  s.inputLights.emitterSamples = 0;
  return s;
}

Frame renderScene(const Scene& scene, const RenderSettings& settings = testSettings()) {
  const SceneGpu gpu(scene);
  Renderer renderer(gpu, settings);
  Frame f;
  f.stats =
      renderer.render(makeCameraView(resolveCamera(scene, settings), settings.image.width, settings.image.height));
  EXPECT_EQ(f.stats.nonFinitePixels, 0u);
  f.final = renderer.readImage(Aov::Final);
  f.direct = renderer.readImage(Aov::Direct);
  f.indirect = renderer.readImage(Aov::Indirect);
  f.albedo = renderer.readImage(Aov::Albedo);
  f.position = renderer.readImage(Aov::Position);
  f.normal = renderer.readImage(Aov::Normal);
  return f;
}

size_t coveredPixels(const Frame& f) {
  size_t n = 0;
  for (const glm::vec4& p : f.position.pixels) n += p.w > 0.0f;
  return n;
}

double maxAbsDifference(const ImageRGBA& a, const ImageRGBA& b) {
  double m = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    m = std::max(m, double(glm::length(glm::vec3(a.pixels[i]) - glm::vec3(b.pixels[i]))));
  return m;
}

glm::quat lookDown(float degrees) { return glm::angleAxis(glm::radians(-degrees), glm::vec3(1, 0, 0)); }

// ---------------------------------------------------------------------------------------------
// Far from the origin

// A small site (a 4 x 4 floor, a red box, a green wall, a point light, a camera 4 units away), all
// under one root node translated by `offset`: a survey or city model placed in world coordinates.
// With `baked`, the offset is added to the vertex data itself (float accessors, as some exporters
// write georeferenced models) instead of being a node translation (double in the JSON).
std::filesystem::path writeSite(const TempDir& dir, const std::string& name, const glm::dvec3& offset,
                                double znear = 0.1, double zfar = 100.0, bool baked = false) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.7f, 0.7f, 0.7f, 1}));
  const int red = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.1f, 0.1f, 1}));
  const int green = w.addMaterial(MaterialDesc{}.withBaseColor({0.1f, 0.7f, 0.1f, 1}));
  std::vector<PrimitiveDesc> prims = {quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, grey),
                                      box({0.4f, 0.35f, 0.2f}, {0.35f, 0.35f, 0.35f}, red),
                                      quad({-2, 0, -2}, {4, 0, 0}, {0, 2, 0}, green)};
  if (baked)
    for (PrimitiveDesc& p : prims)
      for (glm::vec3& v : p.positions) v = glm::vec3(glm::dvec3(v) + offset);
  const int site =
      w.addNode(NodeDesc{}.named("site").withMesh(w.addMesh(prims)).translated(baked ? -offset : glm::dvec3(0.0)));
  const int lamp =
      w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.withIntensity(6))).translated({-0.5, 1.6, 0.6}));
  const int eye = w.addNode(NodeDesc{}
                                .withCamera(w.addCamera(CameraDesc{}.named("eye").withClip(znear, zfar)))
                                .translated({0, 1.5, 4})
                                .rotated(lookDown(18)));
  w.addNode(NodeDesc{}.named("world").translated(offset).withChildren({site, lamp, eye}));
  return w.write(dir / (name + ".gltf"));
}

TEST_F(GLTest, SceneFarFromTheOriginRendersAsAtTheOrigin) {
  TempDir dir;
  const Scene atOrigin = loadScene(writeSite(dir, "origin", glm::dvec3(0.0)));
  const Frame reference = renderScene(atOrigin);
  ASSERT_GT(coveredPixels(reference), size_t(160 * 90 / 2));
  ASSERT_GT(meanLuminance(reference.indirect), 0.0);
  // Held at every distance: the translation stays in double until the scene origin (a multiple of a
  // power of two near the site) is subtracted (gltf_loader.cpp), so scene space, the BVH, VPLs, the
  // hierarchy and the G-buffer hold the site's coordinates up to a shift of a few units, rounded
  // once to float: the images agree to float rounding of values of the site's size, whatever the
  // distance. Measured 2026-12-01 (160 x 90, 4,000 VPLs): identical albedo AOVs; final relative
  // RMSE 2.1e-6 at 1e3, 0 at 1e5 and 1e6 (their origins happen to leave the same float values).
  for (double distance : {1e3, 1e5, 1e6}) {
    SCOPED_TRACE("translated by " + std::to_string(distance));
    const glm::dvec3 offset(distance, 0.37 * distance, -0.61 * distance);
    const Scene far = loadScene(writeSite(dir, "far", offset));
    EXPECT_LE(glm::length(far.origin - offset), 8.0) << "scene space is not near the site";
    const Frame f = renderScene(far);
    EXPECT_EQ(coveredPixels(f), coveredPixels(reference));
    const double albedoError = maxAbsDifference(f.albedo, reference.albedo);
    const double finalError = relativeRmse(f.final, reference.final);
    std::printf("[ far      ] %.0e: albedo max diff %.2e, final relative RMSE %.2e, max diff %.2e\n", distance,
                albedoError, finalError, maxAbsDifference(f.final, reference.final));
    EXPECT_LE(albedoError, 1e-6);
    EXPECT_LE(finalError, 1e-3);
  }
}

TEST_F(GLTest, SceneWithFarCoordinatesInItsVertexDataRendersToTheFilesPrecision) {
  // The same site with the offset written into float vertex data (the site node translated back by
  // -offset in double, so the camera and light sit where they did): now the file itself rounds each
  // vertex to a float ulp of the offset, 6e-5 at 1e3, 7.8e-3 at 1e5, 6.3e-2 at 1e6, against a pixel
  // footprint of about 0.04 at the camera's distance. The renderer adds nothing to that rounding,
  // so the image may differ only where the file's geometry moved: at edges from 1e5 on, by up to
  // 1.7 pixels at 1e6. Bounds measured 2026-12-01, printed below.
  TempDir dir;
  const Frame reference = renderScene(loadScene(writeSite(dir, "origin", glm::dvec3(0.0))));
  for (double distance : {1e3, 1e5, 1e6}) {
    SCOPED_TRACE("vertex data at " + std::to_string(distance));
    const Frame f = renderScene(loadScene(writeSite(dir, "baked", glm::dvec3(distance, 0, 0), 0.1, 100.0, true)));
    const double coverage = double(coveredPixels(f)) / double(coveredPixels(reference));
    const double error = relativeRmse(f.final, reference.final);
    std::printf("[ baked    ] %.0e: coverage ratio %.4f, final relative RMSE %.2e\n", distance, coverage, error);
    EXPECT_NEAR(coverage, 1.0, distance < 1e4 ? 1e-3 : 0.02);
    EXPECT_LE(error, distance < 1e4 ? 1e-3 : distance < 1e6 ? 0.05 : 0.2);
  }
}

TEST_F(GLTest, ExtremeClipPlanesRenderLikeOrdinaryOnes) {
  // znear/zfar = 1e-3/1e7 (a ratio of 1e10) against 0.1/100, with a decal 0.1 mm above a floor about
  // 4 m away. Its depth differs from the floor's by n dd / d^2 ~ 1e-8: below a float ulp near 1 (6e-8)
  // where conventional depth puts it at this near plane (the decal fights the floor: checked by
  // swapping in a conventional projection, 2026-12-01), hundreds of ulps near n/d where reversed Z
  // puts it. The decal must win everywhere, as with ordinary clip planes.
  TempDir dir;
  const auto write = [&](const std::string& name, double znear, double zfar) {
    GltfWriter w;
    const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.7f, 0.7f, 0.7f, 1}));
    const int blue = w.addMaterial(MaterialDesc{}.withBaseColor({0.1f, 0.2f, 0.9f, 1}));
    w.addNode(NodeDesc{}.withMesh(
        w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, grey), quad({-1, 1e-4f, 1}, {2, 0, 0}, {0, 0, -2}, blue)})));
    w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.withIntensity(6))).translated({0, 2, 0}));
    w.addNode(NodeDesc{}
                  .withCamera(w.addCamera(CameraDesc{}.named("eye").withClip(znear, zfar)))
                  .translated({0, 1.5, 4})
                  .rotated(lookDown(25)));
    return loadScene(w.write(dir / (name + ".gltf")));
  };
  const Frame ordinary = renderScene(write("ordinary", 0.1, 100.0));
  const Frame extreme = renderScene(write("extreme", 1e-3, 1e7));
  const Scene infiniteScene = write("infinite", 1e-3, 0.0);  // no zfar in the file: infinite projection
  EXPECT_EQ(infiniteScene.cameras[0].zfar, std::numeric_limits<float>::max());
  const Frame infinite = renderScene(infiniteScene);
  EXPECT_LE(maxAbsDifference(infinite.albedo, ordinary.albedo), 1e-6);
  size_t decal = 0;
  for (size_t i = 0; i < ordinary.albedo.pixels.size(); ++i) {
    const glm::vec4 p = ordinary.position.pixels[i];
    if (p.w > 0 && std::abs(p.x) < 0.95f && std::abs(p.z) < 0.95f) {  // inside the decal, away from its edge
      ++decal;
      EXPECT_NEAR(extreme.albedo.pixels[i].b, 0.9f, 1e-3f) << "the floor shows through the decal at pixel " << i;
      EXPECT_NEAR(ordinary.albedo.pixels[i].b, 0.9f, 1e-3f);
    }
  }
  EXPECT_GT(decal, size_t(500));
  const double albedoError = maxAbsDifference(extreme.albedo, ordinary.albedo);
  const double finalError = relativeRmse(extreme.final, ordinary.final);
  std::printf("[ clip     ] 1e-3/1e7 vs 0.1/100: albedo max diff %.2e, final relative RMSE %.2e\n", albedoError,
              finalError);
  EXPECT_LE(albedoError, 1e-6);
  EXPECT_LE(finalError, 1e-3);
}

// ---------------------------------------------------------------------------------------------
// alphaMode MASK

// A 4 x 1 texture whose left half is transparent (alpha 0) and right half opaque.
int addHalfTransparentTexture(GltfWriter& w) {
  const std::vector<std::uint8_t> rgba = {255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255};
  return w.addTexture(w.addImageEmbedded(encodePng(4, 1, rgba)));
}

// A grey floor, a box for bounds, a sun straight down and, 1 m above the floor, a 2 x 2 quad of
// `blocker` material (or none); the camera sees the floor beside and through the quad.
Scene writeMaskScene(const TempDir& dir, const std::string& name, std::function<int(GltfWriter&)> blocker) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 1}));
  std::vector<PrimitiveDesc> prims = {quad({-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, grey),
                                      box({3.5f, 1.0f, -3.5f}, {0.5f, 1.0f, 0.5f}, grey)};
  if (blocker) prims.push_back(quad({-1, 1, 1}, {2, 0, 0}, {0, 0, -2}, blocker(w)));
  w.addNode(NodeDesc{}.withMesh(w.addMesh(prims)));
  w.addNode(NodeDesc{}
                .withLight(w.addLight(LightDesc{}.ofType("directional").withIntensity(3)))
                .rotated(glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))));  // -Z turned to -Y: straight down
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("eye").withYfov(1.0)))
                .translated({0, 4, 5})
                .rotated(lookDown(40)));
  return loadScene(w.write(dir / (name + ".gltf")));
}

TEST_F(GLTest, AlphaMaskCutsOutTheSurfaceAndItsShadow) {
  TempDir dir;
  const Scene scene = writeMaskScene(dir, "mask", [](GltfWriter& w) {
    return w.addMaterial(MaterialDesc{}.withBaseColorTexture(addHalfTransparentTexture(w)).withAlphaMask(0.5));
  });
  ASSERT_EQ(scene.materials[1].alphaMode, AlphaMode::Mask);
  const Frame f = renderScene(scene);
  const float lit = 3.0f * 0.5f / float(kPi);  // E rho / pi under the sun at normal incidence
  size_t quadLeft = 0, quadRight = 0, floorUnderHole = 0, floorInShadow = 0;
  for (size_t i = 0; i < f.position.pixels.size(); ++i) {
    const glm::vec4 p = f.position.pixels[i];
    if (p.w == 0) continue;
    // The quad's texture: u = (x + 1) / 2; u < 0.5 is cut out (x < 0). Margins skip the filtered edge.
    if (std::abs(p.y - 1.0f) < 1e-3f && std::abs(p.z) < 1.0f) {
      if (p.x < -0.2f) ++quadLeft;
      if (p.x > 0.2f) ++quadRight;
    }
    if (std::abs(p.y) < 1e-3f && std::abs(p.z) < 0.8f && std::abs(p.x) > 0.2f && std::abs(p.x) < 0.8f) {
      const float direct = f.direct.pixels[i].g;
      if (p.x < 0) {  // under the cut-out half: the sun reaches the floor
        ++floorUnderHole;
        EXPECT_NEAR(direct, lit, 0.01f * lit) << "pixel " << i << " at x = " << p.x;
      } else {  // under the opaque half: shadow
        ++floorInShadow;
        EXPECT_EQ(direct, 0.0f) << "pixel " << i << " at x = " << p.x;
      }
    }
  }
  EXPECT_EQ(quadLeft, 0u) << "the camera sees the cut-out half";
  EXPECT_GT(quadRight, 100u);
  EXPECT_GT(floorUnderHole, 50u) << "the floor under the cut-out is not visible: test set-up";
  EXPECT_GT(floorInShadow, 20u) << "the floor under the opaque half is not visible: test set-up";
}

TEST_F(GLTest, FullyCutOutQuadIsInvisibleToCameraShadowsAndVplPaths) {
  // Alpha from the base colour factor (0.2 < cutoff 0.5): nothing of the quad may remain. The VPL
  // paths then take the same steps as without it (same seed), so every AOV matches the empty scene;
  // the same quad opaque changes them a lot (the test can tell).
  TempDir dir;
  const Frame without = renderScene(writeMaskScene(dir, "without", nullptr));
  const Frame cutOut = renderScene(writeMaskScene(dir, "cutout", [](GltfWriter& w) {
    return w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 0.2f}).withAlphaMask(0.5));
  }));
  const Frame opaque = renderScene(writeMaskScene(dir, "opaque", [](GltfWriter& w) {
    return w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 0.2f}));
  }));
  EXPECT_LE(maxAbsDifference(cutOut.albedo, without.albedo), 0.0);
  EXPECT_LE(maxAbsDifference(cutOut.direct, without.direct), 1e-6);
  EXPECT_EQ(cutOut.stats.lights.vpls, without.stats.lights.vpls);
  const double indirectError = relativeRmse(cutOut.indirect, without.indirect);
  const double opaqueError = relativeRmse(opaque.indirect, without.indirect);
  std::printf("[ mask     ] indirect relative RMSE, cut-out vs without: %.2e; opaque vs without: %.2e\n", indirectError,
              opaqueError);
  EXPECT_LE(indirectError, 1e-4);
  EXPECT_GT(opaqueError, 5e-3);
}

TEST_F(GLTest, CutOutPartOfAnEmissiveSurfaceEmitsNothing) {
  // An emissive 2 x 2 quad facing down over a floor, seen from above (its single-sided back is culled),
  // lighting the floor through emitter samples alone. With its left half cut out, the floor must get
  // half the light: the view and the quad are symmetric in x, so each half lights it equally.
  TempDir dir;
  const auto render = [&](const std::string& name, bool halfCutOut) {
    GltfWriter w;
    const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 1}));
    MaterialDesc lamp = MaterialDesc{}.withEmission({1, 1, 1}, 5.0f);
    if (halfCutOut) lamp.withBaseColorTexture(addHalfTransparentTexture(w)).withAlphaMask(0.5);
    const int emissive = w.addMaterial(lamp);
    w.addNode(NodeDesc{}.withMesh(
        w.addMesh({quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, grey), quad({-1, 1, -1}, {2, 0, 0}, {0, 0, 2}, emissive)})));
    w.addNode(NodeDesc{}
                  .withCamera(w.addCamera(CameraDesc{}.named("top").withYfov(1.2)))
                  .translated({0, 4, 0})
                  .rotated(glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))));
    RenderSettings s = testSettings();
    s.inputLights.vpls = 0;
    s.inputLights.emitterSamples = 16384;
    s.shadows.samples = 0;
    return renderScene(loadScene(w.write(dir / (name + ".gltf"))), s);
  };
  const Frame full = render("full", false), half = render("half", true);
  const auto floorLight = [](const Frame& f) {
    double sum = 0;
    for (size_t i = 0; i < f.position.pixels.size(); ++i)
      if (f.position.pixels[i].w > 0 && std::abs(f.position.pixels[i].y) < 1e-3f)
        sum += luminance(f.indirect.pixels[i]);
    return sum;
  };
  const double ratio = floorLight(half) / floorLight(full);
  std::printf("[ mask     ] emissive quad half cut out: floor light ratio %.4f (expected 0.5)\n", ratio);
  EXPECT_GT(floorLight(full), 0.0);
  EXPECT_NEAR(ratio, 0.5, 0.03);
}

// ---------------------------------------------------------------------------------------------
// doubleSided, COLOR_0, KHR_texture_transform, TEXCOORD_1

// A 2 x 2 quad in the plane z = 0, front face towards +Z (the camera at z = 3) or -Z, uv (0, 0) at
// the top left as the camera sees it. Corners: facing +Z BL, BR, TR, TL; facing -Z BL, TL, TR, BR.
PrimitiveDesc facingQuad(float facing, int material) {
  if (facing > 0) {
    PrimitiveDesc q = quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, material);
    q.texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    return q;
  }
  PrimitiveDesc q = quad({-1, -1, 0}, {0, 2, 0}, {2, 0, 0}, material);
  q.texcoords = {{0, 1}, {0, 0}, {1, 0}, {1, 1}};
  return q;
}

// The quad of facingQuad, a light and a camera at z = 3 looking at it, nothing else.
Scene writeFacingQuad(const TempDir& dir, const std::string& name, float facing, MaterialDesc material,
                      std::function<void(PrimitiveDesc&)> edit = nullptr) {
  GltfWriter w;
  PrimitiveDesc q = facingQuad(facing, w.addMaterial(material));
  if (edit) edit(q);
  w.addNode(NodeDesc{}.withMesh(w.addMesh({q})));
  w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.withIntensity(4))).translated({0, 0, 2}));
  w.addNode(NodeDesc{}.withCamera(w.addCamera(CameraDesc{}.named("eye").withYfov(0.9))).translated({0, 0, 3}));
  return loadScene(w.write(dir / (name + ".gltf")));
}

TEST_F(GLTest, SingleSidedBackFacesAreCulledDoubleSidedShowBothSides) {
  TempDir dir;
  const MaterialDesc white = MaterialDesc{}.withBaseColor({0.8f, 0.8f, 0.8f, 1});
  const Frame front = renderScene(writeFacingQuad(dir, "front", +1, white));
  const Frame back = renderScene(writeFacingQuad(dir, "back", -1, white));
  const Frame backTwoSided = renderScene(writeFacingQuad(dir, "back2", -1, MaterialDesc(white).twoSided()));
  EXPECT_GT(coveredPixels(front), 1000u);
  EXPECT_EQ(coveredPixels(back), 0u) << "a single-sided quad seen from behind must not be drawn";
  EXPECT_EQ(coveredPixels(backTwoSided), coveredPixels(front));
  // Seen from behind, a double-sided surface shades with its normal reversed: towards the camera.
  for (size_t i = 0; i < backTwoSided.normal.pixels.size(); ++i) {
    if (backTwoSided.position.pixels[i].w > 0) {
      ASSERT_GT(backTwoSided.normal.pixels[i].z, 0.99f) << "pixel " << i;
    }
  }
  EXPECT_NEAR(meanLuminance(backTwoSided.final), meanLuminance(front.final), 1e-3 * meanLuminance(front.final));
}

// Albedo at the quad point with texture coordinate (u, v) (the quad facing the camera, uv (0,0) top left).
glm::vec3 albedoAt(const Frame& f, float u, float v) {
  // The pixel whose G-buffer position is nearest to the quad point (no projection by hand).
  const glm::vec3 target(-1.0f + 2.0f * u, 1.0f - 2.0f * v, 0.0f);
  size_t best = 0;
  float bestDistance = 1e30f;
  for (size_t i = 0; i < f.position.pixels.size(); ++i) {
    if (f.position.pixels[i].w == 0) continue;
    const float d = glm::length(glm::vec3(f.position.pixels[i]) - target);
    if (d < bestDistance) bestDistance = d, best = i;
  }
  EXPECT_LT(bestDistance, 0.05f);
  return glm::vec3(f.albedo.pixels[best]);
}

// 2 x 2 texels, rows top-down: red, green / blue, white.
int addQuadrantTexture(GltfWriter& w) {
  const std::vector<std::uint8_t> rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  return w.addTexture(w.addImageEmbedded(encodePng(2, 2, rgba)));
}

void expectColor(const glm::vec3& got, const glm::vec3& expected, const char* what) {
  EXPECT_LT(glm::length(got - expected), 0.05f) << what << ": (" << got.r << ", " << got.g << ", " << got.b << ")";
}

TEST_F(GLTest, VertexColoursMultiplyAlbedoForCameraAndVpls) {
  TempDir dir;
  // Camera: COLOR_0 left red, right green, times the factor.
  const Frame f =
      renderScene(writeFacingQuad(dir, "colours", +1, MaterialDesc{}.withBaseColor({1, 1, 1, 1}), [](PrimitiveDesc& q) {
        q.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 1, 0, 1}, {1, 0, 0, 1}};  // corners: BL, BR, TR, TL
      }));
  expectColor(albedoAt(f, 0.05f, 0.5f), {0.95f, 0.05f, 0.0f}, "left edge");
  expectColor(albedoAt(f, 0.95f, 0.5f), {0.05f, 0.95f, 0.0f}, "right edge");
  expectColor(albedoAt(f, 0.5f, 0.5f), {0.5f, 0.5f, 0.0f}, "centre");

  // VPLs: a white floor lit only by light bounced off a wall whose factor is white and whose COLOR_0
  // is red. Coloured by the vertex colour, the VPLs light the floor red; ignoring it, white.
  GltfWriter w;
  const int white = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.8f, 0.8f, 1}));
  PrimitiveDesc wall = quad({-2, 0, -1}, {4, 0, 0}, {0, 2, 0}, white);
  wall.colors.assign(4, glm::vec4(1, 0, 0, 1));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -3}, white), wall})));
  // A spot light aimed at the wall only (the floor gets no direct light).
  w.addNode(NodeDesc{}
                .withLight(w.addLight(LightDesc{}.ofType("spot").withIntensity(20).withCone(0.1, 0.2)))
                .translated({0, 1, 1.5}));
  w.addNode(
      NodeDesc{}.withCamera(w.addCamera(CameraDesc{}.named("eye"))).translated({0, 2.5, 3}).rotated(lookDown(45)));
  const Frame bounce = renderScene(loadScene(w.write(dir / "bounce.gltf")));
  glm::dvec3 floorIndirect(0.0);
  for (size_t i = 0; i < bounce.position.pixels.size(); ++i)
    if (bounce.position.pixels[i].w > 0 && std::abs(bounce.position.pixels[i].y) < 1e-3f)
      floorIndirect += glm::dvec3(bounce.indirect.pixels[i]);
  EXPECT_GT(floorIndirect.r, 0.0);
  EXPECT_LT(floorIndirect.g, 1e-3 * floorIndirect.r) << "the floor's bounced light is not the wall's vertex colour";
}

TEST_F(GLTest, TextureTransformAndTexcoord1SelectTheTexelsGltfDefines) {
  TempDir dir;
  const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
  const auto render = [&](const std::string& name, std::function<MaterialDesc(int)> material,
                          std::function<void(PrimitiveDesc&)> edit = nullptr) {
    GltfWriter scene;
    const int t = addQuadrantTexture(scene);
    const int m = scene.addMaterial(material(t));
    PrimitiveDesc q = facingQuad(+1, m);
    if (edit) edit(q);
    scene.addNode(NodeDesc{}.withMesh(scene.addMesh({q})));
    scene.addNode(NodeDesc{}.withLight(scene.addLight(LightDesc{}.withIntensity(4))).translated({0, 0, 2}));
    scene.addNode(
        NodeDesc{}.withCamera(scene.addCamera(CameraDesc{}.named("eye").withYfov(0.9))).translated({0, 0, 3}));
    return renderScene(loadScene(scene.write(dir / (name + ".gltf"))));
  };
  const auto plain = [](int t) { return MaterialDesc{}.withBaseColorTexture(t); };
  const Frame untransformed = render("plain", plain);
  expectColor(albedoAt(untransformed, 0.25f, 0.25f), red, "plain, top left");
  expectColor(albedoAt(untransformed, 0.75f, 0.75f), white, "plain, bottom right");

  // offset (0.5, 0), scale (0.5, 1): u' = 0.5 u + 0.5, only the right column. Points are chosen where
  // the transformed uv falls on texel centres (the 2 x 2 texture is filtered bilinearly in between).
  const Frame shifted = render("shifted", [](int t) {
    return MaterialDesc{}.withBaseColorTexture(t).withBaseColorTransform(
        {{"offset", {0.5, 0.0}}, {"scale", {0.5, 1.0}}});
  });
  expectColor(albedoAt(shifted, 0.5f, 0.25f), green, "offset+scale, top centre");
  expectColor(albedoAt(shifted, 0.5f, 0.75f), white, "offset+scale, bottom centre");

  // rotation pi/2, counter-clockwise in uv (the extension's matrix): (u, v) -> (-v, u). At (0.25, 0.25)
  // that is (-0.25, 0.25) -> wrapped (0.75, 0.25): green (the opposite sense would give blue).
  const Frame rotated = render("rotated", [](int t) {
    return MaterialDesc{}.withBaseColorTexture(t).withBaseColorTransform({{"rotation", kPi / 2}});
  });
  expectColor(albedoAt(rotated, 0.25f, 0.25f), green, "rotated, top left");
  expectColor(albedoAt(rotated, 0.75f, 0.75f), blue, "rotated, bottom right");

  // TEXCOORD_1 where the texture asks for it: TEXCOORD_0 points at the red texel everywhere.
  const Frame second = render(
      "texcoord1", [](int t) { return MaterialDesc{}.withBaseColorTexture(t, 1); },
      [](PrimitiveDesc& q) {
        q.texcoords1 = q.texcoords;
        q.texcoords.assign(4, glm::vec2(0.25f, 0.25f));
      });
  expectColor(albedoAt(second, 0.75f, 0.25f), green, "TEXCOORD_1, top right");
  expectColor(albedoAt(second, 0.25f, 0.75f), blue, "TEXCOORD_1, bottom left");
  // The transform's texCoord overrides textureInfo.texCoord (KHR_texture_transform).
  const Frame overridden = render(
      "override",
      [](int t) {
        return MaterialDesc{}.withBaseColorTexture(t, 0).withBaseColorTransform({{"texCoord", 1}});
      },
      [](PrimitiveDesc& q) {
        q.texcoords1 = q.texcoords;
        q.texcoords.assign(4, glm::vec2(0.25f, 0.25f));
      });
  expectColor(albedoAt(overridden, 0.75f, 0.75f), white, "texCoord override, bottom right");
}

// ---------------------------------------------------------------------------------------------
// KHR_mesh_quantization

TEST_F(GLTest, QuantizedMeshRendersLikeTheFloatMesh) {
  // The site's box and floor with POSITION as normalized SHORT (dequantized by the node's scale) and
  // NORMAL as normalized BYTE, against the same mesh in float.
  TempDir dir;
  const auto write = [&](const std::string& name, bool quantized) {
    GltfWriter w;
    const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.7f, 0.7f, 0.7f, 1}));
    const int red = w.addMaterial(MaterialDesc{}.withBaseColor({0.8f, 0.1f, 0.1f, 1}));
    const float extent = 2.0f;  // positions / extent lie in [-1, 1]
    std::vector<PrimitiveDesc> prims = {quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, grey),
                                        box({0.4f, 0.35f, 0.2f}, {0.35f, 0.35f, 0.35f}, red)};
    for (PrimitiveDesc& p : prims) {
      for (glm::vec3& v : p.positions) v /= extent;
      if (quantized) {
        p.positionType = gltf::kShort;
        p.positionNormalized = true;
        p.normalType = gltf::kByte;
      }
    }
    w.addNode(NodeDesc{}.withMesh(w.addMesh(prims)).scaled(glm::vec3(extent)));
    w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.withIntensity(6))).translated({-0.5, 1.6, 0.6}));
    w.addNode(
        NodeDesc{}.withCamera(w.addCamera(CameraDesc{}.named("eye"))).translated({0, 1.5, 4}).rotated(lookDown(18)));
    return loadScene(w.write(dir / (name + ".gltf")));
  };
  const Scene floatScene = write("float", false), quantizedScene = write("quantized", true);
  // Dequantized positions agree with the float ones to the SHORT step (extent / 32767).
  ASSERT_EQ(floatScene.positions.size(), quantizedScene.positions.size());
  for (size_t i = 0; i < floatScene.positions.size(); ++i)
    ASSERT_LE(glm::length(glm::dvec3(floatScene.positions[i]) + floatScene.origin -
                          glm::dvec3(quantizedScene.positions[i]) - quantizedScene.origin),
              2.0 * 2.0 / 32767.0);
  const Frame a = renderScene(floatScene), b = renderScene(quantizedScene);
  EXPECT_EQ(coveredPixels(a), coveredPixels(b));
  const double error = relativeRmse(b.final, a.final);
  std::printf("[ quantize ] final relative RMSE quantized vs float: %.2e\n", error);
  EXPECT_LE(error, 1e-2);
}

}  // namespace
}  // namespace lgh::test
