// Scene loading (render/scene/gltf_loader.cpp, camera.cpp): the shared reference scenes, the
// project's Cornell box and synthetic files written by gltf_writer.h that exercise one feature each.
// Broken files (SceneLoadError) and sparse accessors are in tests/loader/scene_errors_test.cpp, run
// under AddressSanitizer + UBSan.
// No GL context needed: plain TEST.
#include <chrono>
#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <set>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "render/scene/scene.h"

namespace lgh::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr float kPi = 3.14159265358979f;

::testing::AssertionResult near3(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
  if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(eps)))) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") != (" << b.x << ", " << b.y
                                       << ", " << b.z << ") within " << eps;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

bool anyWarningContains(const Scene& scene, const std::string& part) {
  for (const std::string& w : scene.warnings)
    if (contains(w, part)) return true;
  return false;
}

// Every triangle's winding (counter-clockwise = front) agrees with its vertex normals, and all
// normals are unit length: what shading and back-face logic rely on.
void expectConsistentTriangles(const Scene& scene) {
  ASSERT_EQ(scene.normals.size(), scene.positions.size());
  ASSERT_EQ(scene.texcoords.size(), scene.positions.size());
  for (const glm::vec3& n : scene.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    const std::uint32_t a = scene.indices[3 * t], b = scene.indices[3 * t + 1], c = scene.indices[3 * t + 2];
    const glm::vec3 geometric =
        glm::cross(scene.positions[b] - scene.positions[a], scene.positions[c] - scene.positions[a]);
    if (glm::length(geometric) < 1e-12f) continue;
    const glm::vec3 shading = scene.normals[a] + scene.normals[b] + scene.normals[c];
    ASSERT_GT(glm::dot(geometric, shading), 0.0f) << "triangle " << t << " is wound against its normals";
  }
}

void expectRangesCoverTriangles(const Scene& scene) {
  ASSERT_EQ(scene.triangleMaterials.size(), scene.triangleCount());
  std::uint32_t next = 0;
  std::set<std::uint32_t> seen;
  for (const MaterialRange& r : scene.materialRanges) {
    EXPECT_EQ(r.firstTriangle, next) << "ranges must be contiguous and in order";
    EXPECT_GT(r.triangleCount, 0u);
    EXPECT_LT(r.material, scene.materials.size());
    EXPECT_TRUE(seen.insert(r.material).second) << "material " << r.material << " has two ranges";
    for (std::uint32_t t = r.firstTriangle; t < r.firstTriangle + r.triangleCount; ++t)
      ASSERT_EQ(scene.triangleMaterials[t], r.material);
    next += r.triangleCount;
  }
  EXPECT_EQ(next, scene.triangleCount());
  for (std::uint32_t i : scene.indices) ASSERT_LT(i, scene.positions.size());
}

void expectBounds(const Scene& scene, const glm::vec3& lo, const glm::vec3& hi, float eps) {
  EXPECT_TRUE(near3(scene.bounds.min, lo, eps));
  EXPECT_TRUE(near3(scene.bounds.max, hi, eps));
  Bounds recomputed;
  for (std::uint32_t i : scene.indices) recomputed.extend(scene.positions[i]);
  EXPECT_TRUE(near3(recomputed.min, scene.bounds.min, 0.0f));
  EXPECT_TRUE(near3(recomputed.max, scene.bounds.max, 0.0f));
}

Scene loadTimed(const fs::path& path, const char* label) {
  const auto start = std::chrono::steady_clock::now();
  Scene scene = loadScene(path);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ SCENE    ] %s: %zu triangles, %zu lights, loaded in %.1f ms\n", label, scene.triangleCount(),
              scene.lights.size(), ms);
  ::testing::Test::RecordProperty("load_ms", std::to_string(ms));
  return scene;
}

// ------------------------------------------------------------------------------------------------
// Shared reference scenes (skipped when ../shared/scenes is absent)

TEST(SceneShared, CornellEmissive) {
  LGH_REQUIRE_SHARED_SCENE(path, "cornell_emissive/cornell_emissive.gltf");
  const Scene scene = loadTimed(path, "cornell_emissive");
  EXPECT_EQ(scene.triangleCount(), 12156u);
  expectRangesCoverTriangles(scene);
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));
  size_t emissive = 0;
  for (const Material& m : scene.materials) emissive += m.isEmissive();
  EXPECT_EQ(emissive, 13u);

  // emission = emissiveFactor * emissiveStrength, material by material, against the JSON itself.
  std::ifstream in(path);
  const json doc = json::parse(in);
  ASSERT_EQ(doc["materials"].size(), scene.materials.size());
  size_t withStrength = 0;
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const json& m = doc["materials"][i];
    glm::vec3 expected(0.0f);
    if (m.contains("emissiveFactor"))
      expected = {m["emissiveFactor"][0], m["emissiveFactor"][1], m["emissiveFactor"][2]};
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_emissive_strength")) {
      expected *= m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"].get<float>();
      withStrength += expected != glm::vec3(0.0f) &&
                      m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"].get<float>() != 1.0f;
    }
    EXPECT_TRUE(near3(scene.materials[i].emission, expected, 1e-5f)) << scene.materials[i].name;
  }
  EXPECT_GT(withStrength, 0u) << "the file should exercise a strength other than 1";
  // One value spelled out: Material.001 is emissiveFactor (1, 0, 0) with strength 2.
  EXPECT_TRUE(near3(scene.materials[1].emission, glm::vec3(2.0f, 0.0f, 0.0f)));

  const Camera& front = scene.camera("front");
  EXPECT_TRUE(near3(front.position, glm::vec3(0.0f, 1.0f, 3.9f), 1e-5f));
  EXPECT_TRUE(near3(-front.orientation[2], glm::vec3(0, 0, -1), 1e-5f));
  EXPECT_NEAR(front.yfov, 0.6859144f, 1e-6f);
  expectBounds(scene, {-1.02f, 0.0f, -1.04f}, {1.0f, 1.99f, 1.05f}, 0.011f);
}

TEST(SceneShared, SponzaSun) {
  LGH_REQUIRE_SHARED_SCENE(path, "sponza_sun/sponza_sun.gltf");
  const Scene scene = loadTimed(path, "sponza_sun");
  EXPECT_EQ(scene.triangleCount(), 66447u);
  expectRangesCoverTriangles(scene);
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));
  ASSERT_EQ(scene.lights.size(), 1u);
  const PunctualLight& sun = scene.lights[0];
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_EQ(sun.name, "sun");
  EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-5f);
  EXPECT_LT(sun.direction.y, -0.5f) << "the sun shines down through the roof";
  EXPECT_TRUE(near3(sun.intensity, 8.0f * glm::vec3(1.0f, 0.95f, 0.85f), 1e-5f));
  EXPECT_NO_THROW(scene.camera("atrium"));
  EXPECT_NO_THROW(scene.camera("gallery"));
  EXPECT_EQ(scene.camera("atrium").aspectRatio, 16.0f / 9.0f);
  expectBounds(scene, {-17.4f, -0.9f, -7.8f}, {17.4f, 15.7f, 7.8f}, 0.051f);
}

TEST(SceneShared, Sponza4096Points) {
  LGH_REQUIRE_SHARED_SCENE(path, "sponza_4096_points/sponza_4096_points.gltf");
  const Scene scene = loadTimed(path, "sponza_4096_points");
  EXPECT_EQ(scene.triangleCount(), 66447u);
  ASSERT_EQ(scene.lights.size(), 4096u);
  for (const PunctualLight& l : scene.lights) {
    ASSERT_EQ(l.type, LightType::Point);
    ASSERT_TRUE(glm::all(glm::greaterThanEqual(l.position, scene.bounds.min)) &&
                glm::all(glm::lessThanEqual(l.position, scene.bounds.max)))
        << l.position.x << " " << l.position.y << " " << l.position.z;
    ASSERT_GT(l.intensity.r + l.intensity.g + l.intensity.b, 0.0f);
  }
  // Spot check one light against the JSON: light 4095 at node translation, color * intensity.
  std::ifstream in(path);
  const json doc = json::parse(in);
  const json& node = doc["nodes"].back();
  ASSERT_EQ(node["extensions"]["KHR_lights_punctual"]["light"].get<int>(), 4095);
  const json& light = doc["extensions"]["KHR_lights_punctual"]["lights"][4095];
  const PunctualLight& loaded = scene.lights.back();
  EXPECT_TRUE(near3(loaded.position, {node["translation"][0], node["translation"][1], node["translation"][2]}));
  EXPECT_TRUE(near3(loaded.intensity, light["intensity"].get<float>() *
                                          glm::vec3(light["color"][0], light["color"][1], light["color"][2])));
  EXPECT_NO_THROW(scene.camera("atrium"));
  expectBounds(scene, {-17.4f, -0.9f, -7.8f}, {17.4f, 15.7f, 7.8f}, 0.051f);
}

// ------------------------------------------------------------------------------------------------
// The project's default scene

TEST(SceneCornellBox, LoadsAsAuthored) {
  const fs::path path = sourceDir() / "data" / "cornell_box.gltf";
  const Scene scene = loadScene(path);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  EXPECT_EQ(scene.triangleCount(), 30u);  // 15 quads: floor, ceiling, 3 walls, 2 blocks x 5 faces
  expectRangesCoverTriangles(scene);
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));
  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_TRUE(near3(glm::vec3(scene.materials[0].baseColorFactor), {0.725f, 0.71f, 0.68f}));
  EXPECT_TRUE(near3(glm::vec3(scene.materials[1].baseColorFactor), {0.63f, 0.065f, 0.05f}));
  EXPECT_TRUE(near3(glm::vec3(scene.materials[2].baseColorFactor), {0.14f, 0.45f, 0.091f}));
  for (const Material& m : scene.materials) EXPECT_FALSE(m.isEmissive()) << "the light must not be counted twice";

  // Room surfaces face into the room: classify triangles by the plane all three corners lie on.
  size_t roomTriangles = 0;
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (int c = 0; c < 3; ++c) {
      lo = glm::min(lo, scene.positions[scene.indices[3 * t + c]]);
      hi = glm::max(hi, scene.positions[scene.indices[3 * t + c]]);
    }
    const glm::vec3 n = scene.normals[scene.indices[3 * t]];
    if (hi.y == 0.0f) {
      EXPECT_TRUE(near3(n, {0, 1, 0})) << "floor";
    } else if (lo.y > 0.5487f) {
      EXPECT_TRUE(near3(n, {0, -1, 0})) << "ceiling";
    } else if (lo.z > 0.5591f) {
      EXPECT_TRUE(near3(n, {0, 0, -1})) << "back wall";
    } else if (hi.x == 0.0f) {
      EXPECT_TRUE(near3(n, {1, 0, 0})) << "green wall";
    } else if (lo.x > 0.549f) {
      EXPECT_LT(n.x, -0.99f) << "red wall";
    } else {
      continue;
    }
    ++roomTriangles;
  }
  EXPECT_EQ(roomTriangles, 10u);

  ASSERT_EQ(scene.lights.size(), 1u);
  const PunctualLight& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::Spot);
  EXPECT_TRUE(near3(light.position, {0.278f, 0.5478f, 0.2795f}));
  EXPECT_TRUE(near3(light.direction, {0.0f, -1.0f, 0.0f}));
  EXPECT_NEAR(light.innerConeCos, 1.0f, 1e-6f);
  EXPECT_NEAR(light.outerConeCos, 0.0f, 1e-6f);
  // Floor radiance below the light ~0.5 (luminance of albedo/pi * I/d^2), as the generator says.
  const glm::vec3 radiance = glm::vec3(0.725f, 0.71f, 0.68f) / kPi * light.intensity / (0.5478f * 0.5478f);
  EXPECT_NEAR(glm::dot(radiance, glm::vec3(0.2126f, 0.7152f, 0.0722f)), 0.5f, 0.005f);

  const Camera& front = scene.camera("front");
  EXPECT_TRUE(near3(front.position, {0.278f, 0.273f, -0.8f}));
  EXPECT_TRUE(near3(-front.orientation[2], {0, 0, 1}, 1e-6f)) << "looks into the box (+z)";
  EXPECT_TRUE(near3(front.orientation[1], {0, 1, 0}, 1e-6f));
  EXPECT_NEAR(front.yfov, 2.0f * std::atan(12.5f / 35.0f), 1e-6f);
  EXPECT_EQ(front.aspectRatio, 1.0f);
  // Published extents (the red wall leans out to x = 556 mm at the top).
  expectBounds(scene, {0.0f, 0.0f, 0.0f}, {0.556f, 0.5488f, 0.5592f}, 1e-6f);
}

// ------------------------------------------------------------------------------------------------
// Node transforms

// Is world position p (scene position + Scene::origin) a vertex of the scene?
bool hasPosition(const Scene& scene, const glm::vec3& p) {
  for (const glm::vec3& q : scene.positions)
    if (glm::all(glm::lessThanEqual(glm::abs(glm::dvec3(p) - glm::dvec3(q) - scene.origin), glm::dvec3(1e-5))))
      return true;
  return false;
}

glm::quat axisAngle(float degrees, const glm::vec3& axis) { return glm::angleAxis(glm::radians(degrees), axis); }

TEST(SceneNodes, NestedTransformsWithMirrorKeepNormalsAndWinding) {
  TempDir dir;
  GltfWriter w;
  // A unit quad in the xy plane facing +z, under: scale 0.5 + translate (0,5,0) → translate
  // (10,0,0) + rotate 90° about y → scale (-1, 2, 1) (a mirror). By hand (R_y(90): (x,y,z) →
  // (z, y, -x)): local (1,0,0) → (-1,0,0) → (0,0,1) → (10,0,1) → (5,5,0.5); the normal +z → +x;
  // and the mirror turns the triangles clockwise, so the loader must flip them.
  const int mesh = w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})}, "quad");
  const int leaf = w.addNode(NodeDesc{}.named("mirrored").withMesh(mesh).scaled(glm::vec3{-1, 2, 1}));
  const int middle = w.addNode(NodeDesc{}
                                   .named("middle")
                                   .withChildren(std::vector<int>{leaf})
                                   .translated(glm::vec3{10, 0, 0})
                                   .rotated(axisAngle(90, {0, 1, 0})));
  w.addNode(NodeDesc{}
                .named("top")
                .withChildren(std::vector<int>{middle})
                .translated(glm::vec3{0, 5, 0})
                .scaled(glm::vec3{0.5f, 0.5f, 0.5f}));
  const Scene scene = loadScene(w.write(dir / "nested.gltf"));

  ASSERT_EQ(scene.triangleCount(), 2u);
  std::vector<glm::vec3> expected = {{5, 5, 0}, {5, 5, 0.5f}, {5, 6, 0.5f}, {5, 6, 0}};
  ASSERT_EQ(scene.positions.size(), 4u);
  for (const glm::vec3& e : expected) EXPECT_TRUE(hasPosition(scene, e)) << e.x << " " << e.y << " " << e.z;
  for (const glm::vec3& n : scene.normals) EXPECT_TRUE(near3(n, {1, 0, 0}));
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));

  // The same transform as one matrix (column-major) gives the same result.
  const glm::mat4 m = glm::translate(glm::mat4(1), {0, 5, 0}) * glm::scale(glm::mat4(1), glm::vec3(0.5f)) *
                      glm::translate(glm::mat4(1), {10, 0, 0}) * glm::mat4_cast(axisAngle(90, {0, 1, 0})) *
                      glm::scale(glm::mat4(1), {-1, 2, 1});
  GltfWriter w2;
  const int mesh2 = w2.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  w2.addNode(NodeDesc{}.withMesh(mesh2).withMatrix(std::vector<double>(&m[0][0], &m[0][0] + 16)));
  const Scene fromMatrix = loadScene(w2.write(dir / "matrix.gltf"));
  ASSERT_EQ(fromMatrix.positions.size(), 4u);
  for (const glm::vec3& e : expected) EXPECT_TRUE(hasPosition(fromMatrix, e)) << e.x << " " << e.y << " " << e.z;
  EXPECT_EQ(fromMatrix.indices, scene.indices);
}

TEST(SceneNodes, NonUniformScaleUsesInverseTransposeForNormals) {
  TempDir dir;
  GltfWriter w;
  // A 45° slope: normal (−1, 1, 0)/√2. Stretched 4x in x, the surface flattens, so the true
  // normal tilts toward +y: inverse transpose gives (−1/4, 1, 0) normalised; M·n would give (−4, 1).
  PrimitiveDesc slope = quad({0, 0, 0}, {1, 1, 0}, {0, 0, -1});
  const int mesh = w.addMesh({slope});
  w.addNode(NodeDesc{}.withMesh(mesh).scaled(glm::vec3{4, 1, 1}));
  const Scene scene = loadScene(w.write(dir / "scaled.gltf"));
  for (const glm::vec3& n : scene.normals) EXPECT_TRUE(near3(n, glm::normalize(glm::vec3(-0.25f, 1, 0))));
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));
}

TEST(SceneNodes, OnlyTheDefaultSceneIsLoaded) {
  TempDir dir;
  GltfWriter w;
  const int a = w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})})));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({box({0, 0, 0}, {1, 1, 1})})));  // not in the scene
  w.setSceneRoots({a});
  const Scene scene = loadScene(w.write(dir / "roots.gltf"));
  EXPECT_EQ(scene.triangleCount(), 2u);
}

// ------------------------------------------------------------------------------------------------
// Meshes and materials

TEST(SceneMeshes, MultiplePrimitivesAreGroupedByMaterialInStableOrder) {
  TempDir dir;
  GltfWriter w;
  const int red = w.addMaterial(MaterialDesc{}.named("red").withBaseColor(glm::vec4{1, 0, 0, 1}));
  const int blue = w.addMaterial(MaterialDesc{}.named("blue").withBaseColor(glm::vec4{0, 0, 1, 1}));
  w.addMaterial(MaterialDesc{}.named("unused"));
  PrimitiveDesc strip;  // 5 vertices → 3 triangles, all facing +z
  strip.positions = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {1, 1, 5}, {0, 2, 5}};
  strip.normals.assign(5, {0, 0, 1});
  strip.mode = gltf::kTriangleStrip;
  strip.material = blue;
  PrimitiveDesc fan;  // 5 vertices → 3 triangles around vertex 0
  fan.positions = {{0, 0, 9}, {1, 0, 9}, {1, 1, 9}, {0, 1, 9}, {-1, 1, 9}};
  fan.normals.assign(5, {0, 0, 1});
  fan.indices = {0, 1, 2, 3, 4};
  fan.indexType = gltf::kUnsignedByte;
  fan.mode = gltf::kTriangleFan;
  fan.material = red;
  PrimitiveDesc points;
  points.positions = {{0, 0, 0}, {1, 1, 1}};
  points.mode = gltf::kPoints;
  PrimitiveDesc noMaterial = quad({0, 0, 20}, {1, 0, 0}, {0, 1, 0});
  noMaterial.indexType = gltf::kUnsignedShort;
  const int mesh = w.addMesh(
      {quad({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, blue), box({0, 0, -5}, {1, 1, 1}, red), strip, fan, points, noMaterial},
      "mixed");
  w.addNode(NodeDesc{}.named("first").withMesh(mesh));
  w.addNode(NodeDesc{}.named("second").withMesh(mesh).translated(glm::vec3{100, 0, 0}));
  const Scene scene = loadScene(w.write(dir / "mixed.gltf"));

  // Per instance: quad 2 + box 12 + strip 3 + fan 3 + quad 2 = 22; points skipped with a warning.
  EXPECT_EQ(scene.triangleCount(), 44u);
  EXPECT_TRUE(anyWarningContains(scene, "mesh 0 'mixed' primitive 4")) << "points primitive skipped silently";
  expectRangesCoverTriangles(scene);
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));
  ASSERT_EQ(scene.materials.size(), 4u);  // red, blue, unused, + the default for `noMaterial`
  EXPECT_EQ(scene.materials[3].name, "default");
  ASSERT_EQ(scene.materialRanges.size(), 3u);  // "unused" has no range
  EXPECT_EQ(scene.materialRanges[0].material, 0u);
  EXPECT_EQ(scene.materialRanges[0].triangleCount, 2u * (12 + 3));
  EXPECT_EQ(scene.materialRanges[1].material, 1u);
  EXPECT_EQ(scene.materialRanges[1].triangleCount, 2u * (2 + 3));
  EXPECT_EQ(scene.materialRanges[2].material, 3u);
  EXPECT_EQ(scene.materialRanges[2].triangleCount, 4u);

  // Stable order inside "blue": first instance's quad (z=1), its strip (z=5), then the second
  // instance (x >= 100).
  auto triangle = [&](std::uint32_t t) { return scene.positions[scene.indices[3 * t]]; };
  const std::uint32_t b = scene.materialRanges[1].firstTriangle;
  EXPECT_EQ(triangle(b).z, 1.0f);
  EXPECT_EQ(triangle(b + 2).z, 5.0f);
  EXPECT_LT(triangle(b + 4).x, 100.0f);
  EXPECT_GE(triangle(b + 5).x, 100.0f);
  // The fan's triangles all contain its centre vertex (0,0,9).
  const std::uint32_t r = scene.materialRanges[0].firstTriangle;
  for (std::uint32_t t = r + 12; t < r + 15; ++t) {
    bool hasCentre = false;
    for (int c = 0; c < 3; ++c) hasCentre |= scene.positions[scene.indices[3 * t + c]] == glm::vec3(0, 0, 9);
    EXPECT_TRUE(hasCentre) << t;
  }
}

TEST(SceneMeshes, AccessorVariantsReadTheSameData) {
  // Interleaved POSITION/NORMAL (byteStride 24), normalised u8 / u16 texcoords (u8 with stride 4),
  // u8 / u16 / u32 indices and no indices must all give the same triangles and texcoords.
  TempDir dir;
  std::vector<Scene> scenes;
  int variant = 0;
  for (int texcoordType : {gltf::kFloat, gltf::kUnsignedShort, gltf::kUnsignedByte}) {
    for (int indexType : {gltf::kUnsignedByte, gltf::kUnsignedShort, gltf::kUnsignedInt, -1}) {
      PrimitiveDesc p = quad({0, 0, 0}, {2, 0, 0}, {0, 3, 0});
      p.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0.2f, 0.6f}};  // exact in 8 bits: 51/255, 153/255
      p.texcoordType = texcoordType;
      p.interleaved = variant % 2 == 1;
      if (indexType < 0) {  // non-indexed: expand
        PrimitiveDesc expanded = p;
        expanded.positions.clear();
        expanded.normals.clear();
        expanded.texcoords.clear();
        for (std::uint32_t i : p.indices) {
          expanded.positions.push_back(p.positions[i]);
          expanded.normals.push_back(p.normals[i]);
          expanded.texcoords.push_back(p.texcoords[i]);
        }
        expanded.indices.clear();
        p = expanded;
      } else {
        p.indexType = indexType;
      }
      GltfWriter w;
      w.addNode(NodeDesc{}.withMesh(w.addMesh({p})));
      scenes.push_back(loadScene(w.write(dir / ("variant" + std::to_string(variant++) + ".gltf"))));
    }
  }
  auto corners = [](const Scene& s) {
    std::vector<std::pair<glm::vec3, glm::vec2>> out;
    for (std::uint32_t i : s.indices) out.push_back({s.positions[i], s.texcoords[i]});
    return out;
  };
  const auto reference = corners(scenes[0]);
  ASSERT_EQ(reference.size(), 6u);
  for (size_t s = 1; s < scenes.size(); ++s) {
    const auto c = corners(scenes[s]);
    ASSERT_EQ(c.size(), reference.size()) << "variant " << s;
    for (size_t i = 0; i < c.size(); ++i) {
      EXPECT_TRUE(near3(c[i].first, reference[i].first)) << "variant " << s;
      EXPECT_NEAR(c[i].second.x, reference[i].second.x, 1e-6f) << "variant " << s;
      EXPECT_NEAR(c[i].second.y, reference[i].second.y, 1e-6f) << "variant " << s;
    }
  }
}

TEST(SceneMeshes, MissingNormalsGiveFlatNormalsAndDegenerateTrianglesNoNaN) {
  TempDir dir;
  GltfWriter w;
  PrimitiveDesc p;
  p.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0},   // faces +y (counter-clockwise seen from above)
                 {2, 2, 2}, {2, 2, 2}, {2, 2, 2},   // zero area: a point
                 {0, 0, 0}, {1, 1, 1}, {2, 2, 2}};  // zero area: collinear
  w.addNode(NodeDesc{}.withMesh(w.addMesh({p}, "flat")));
  // Also a triangle with a supplied zero normal: replaced, not NaN.
  PrimitiveDesc zeroNormal = quad({0, 0, 3}, {1, 0, 0}, {0, 1, 0});
  zeroNormal.normals[0] = glm::vec3(0.0f);
  w.addNode(NodeDesc{}.withMesh(w.addMesh({zeroNormal}, "zero_normal")));
  const Scene scene = loadScene(w.write(dir / "flat.gltf"));
  EXPECT_EQ(scene.triangleCount(), 5u) << "degenerate triangles are kept";
  EXPECT_TRUE(anyWarningContains(scene, "NORMAL"));
  EXPECT_TRUE(anyWarningContains(scene, "'flat'"));
  EXPECT_TRUE(anyWarningContains(scene, "'zero_normal'"));
  for (const glm::vec3& n : scene.normals) {
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
  }
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(near3(scene.normals[scene.indices[c]], {0, 1, 0}));
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(scene));
}

// ------------------------------------------------------------------------------------------------
// Lights and cameras

TEST(SceneLights, PunctualLightsTakeTheirNodeTransformsAndDefaults) {
  TempDir dir;
  GltfWriter w;
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})})));
  const int point = w.addLight(LightDesc{}.named("bulb"));  // no color / intensity: white, 1
  const int spot = w.addLight(
      LightDesc{}.ofType("spot").withColor(std::vector<double>{1, 0.5, 0.25}).withIntensity(10));  // default cone
  const int narrow = w.addLight(LightDesc{}.named("narrow").ofType("spot").withRange(7).withCone(0.2, 0.5));
  const int sun = w.addLight(LightDesc{}.named("sun").ofType("directional").withIntensity(3));
  const int bulbNode = w.addNode(NodeDesc{}.named("bulb node").withLight(point).translated(glm::vec3{1, 2, 3}));
  const int spotNode = w.addNode(NodeDesc{}
                                     .named("spot node")
                                     .withLight(spot)
                                     .translated(glm::vec3{0, 4, 0})
                                     .rotated(axisAngle(-90, {1, 0, 0})));                            // -z → -y
  const int narrowNode = w.addNode(NodeDesc{}.withLight(narrow).rotated(axisAngle(180, {0, 1, 0})));  // -z → +z
  const int sunNode =
      w.addNode(NodeDesc{}.withLight(sun).rotated(axisAngle(90, {0, 1, 0})).scaled(glm::vec3{3, 3, 3}));  // -z → -x
  w.addNode(NodeDesc{}
                .named("rig")
                .withChildren(std::vector<int>{bulbNode, spotNode, narrowNode, sunNode})
                .translated(glm::vec3{10, 0, 0}));
  const Scene scene = loadScene(w.write(dir / "lights.gltf"));

  ASSERT_EQ(scene.lights.size(), 4u);
  const PunctualLight& l0 = scene.lights[0];
  EXPECT_EQ(l0.name, "bulb");
  EXPECT_EQ(l0.type, LightType::Point);
  EXPECT_TRUE(near3(l0.position, {11, 2, 3}));
  EXPECT_TRUE(near3(l0.intensity, {1, 1, 1}));
  EXPECT_EQ(l0.range, 0.0f);

  const PunctualLight& l1 = scene.lights[1];
  EXPECT_EQ(l1.name, "spot node") << "unnamed light takes its node's name";
  EXPECT_EQ(l1.type, LightType::Spot);
  EXPECT_TRUE(near3(l1.position, {10, 4, 0}));
  EXPECT_TRUE(near3(l1.direction, {0, -1, 0}));
  EXPECT_TRUE(near3(l1.intensity, {10, 5, 2.5f}));
  EXPECT_NEAR(l1.innerConeCos, 1.0f, 1e-6f);               // innerConeAngle 0
  EXPECT_NEAR(l1.outerConeCos, std::cos(kPi / 4), 1e-6f);  // outerConeAngle pi/4

  const PunctualLight& l2 = scene.lights[2];
  EXPECT_TRUE(near3(l2.direction, {0, 0, 1}));
  EXPECT_NEAR(l2.innerConeCos, std::cos(0.2f), 1e-6f);
  EXPECT_NEAR(l2.outerConeCos, std::cos(0.5f), 1e-6f);
  EXPECT_EQ(l2.range, 7.0f);

  const PunctualLight& l3 = scene.lights[3];
  EXPECT_EQ(l3.type, LightType::Directional);
  EXPECT_TRUE(near3(l3.direction, {-1, 0, 0})) << "unit even under a scaled node";
  EXPECT_TRUE(near3(l3.intensity, {3, 3, 3}));
}

TEST(SceneCameras, PerspectiveCamerasFromNodesOrthographicSkipped) {
  TempDir dir;
  GltfWriter w;
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})})));
  const int named = w.addCamera(CameraDesc{}.named("overview").withYfov(0.5).withAspectRatio(1.5).withClip(0.1, 50));
  const int unnamed = w.addCamera(CameraDesc{}.withYfov(1.0));
  const int ortho = w.addCamera(CameraDesc{}.named("plan").ofType("orthographic"));
  const int overviewNode = w.addNode(NodeDesc{}
                                         .named("ignored node name")
                                         .withCamera(named)
                                         .translated(glm::vec3{1, 2, 3})
                                         .rotated(axisAngle(90, {0, 1, 0})));
  const int sideNode =
      w.addNode(NodeDesc{}.named("side").withCamera(unnamed).translated(glm::vec3{0, 1, 0}).scaled(glm::vec3{2, 2, 2}));
  w.addNode(NodeDesc{}.withCamera(ortho));
  w.addNode(NodeDesc{}.withChildren(std::vector<int>{overviewNode, sideNode}).translated(glm::vec3{0, 0, 5}));
  const Scene scene = loadScene(w.write(dir / "cameras.gltf"));

  ASSERT_EQ(scene.cameras.size(), 2u);
  EXPECT_TRUE(anyWarningContains(scene, "orthographic"));
  const Camera& overview = scene.camera("overview");
  EXPECT_TRUE(near3(overview.position, {1, 2, 8}));
  EXPECT_TRUE(near3(-overview.orientation[2], {-1, 0, 0})) << "rotated 90° about y: looks down -x";
  EXPECT_TRUE(near3(overview.orientation[1], {0, 1, 0}));
  EXPECT_TRUE(near3(overview.orientation[0], {0, 0, -1}));
  EXPECT_FLOAT_EQ(overview.yfov, 0.5f);
  EXPECT_FLOAT_EQ(overview.aspectRatio, 1.5f);
  EXPECT_FLOAT_EQ(overview.znear, 0.1f);
  EXPECT_FLOAT_EQ(overview.zfar, 50.0f);
  const Camera& side = scene.camera("side");  // the camera has no name: the node's
  EXPECT_TRUE(near3(side.position, {0, 1, 5}));
  EXPECT_TRUE(near3(side.orientation[0], {1, 0, 0})) << "orthonormal despite the node's scale";
  EXPECT_EQ(side.aspectRatio, 0.0f);

  try {
    scene.camera("nonesuch");
    ADD_FAILURE() << "expected SceneLoadError";
  } catch (const SceneLoadError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(contains(message, "cameras.gltf")) << message;
    EXPECT_TRUE(contains(message, "nonesuch")) << message;
    EXPECT_TRUE(contains(message, "'overview', 'side'")) << message;
  }
}

// ------------------------------------------------------------------------------------------------
// Textures

std::vector<std::uint8_t> checkerPixels() {  // 2x2: red, green / blue, white-ish (top row first)
  return {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 250, 251, 252, 128};
}

TEST(SceneTextures, BaseColorAndEmissivePngsDecodeToTheirPixels) {
  TempDir dir;
  const std::vector<std::uint8_t> pixels = checkerPixels();
  std::ofstream(dir / "albedo map.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(encodePng(2, 2, pixels).data()),
             std::streamsize(encodePng(2, 2, pixels).size()));
  GltfWriter w;
  const int external = w.addTexture(w.addImageUri("albedo%20map.png"));  // URI-encoded file name
  const std::vector<std::uint8_t> glow(4 * 3 * 1, 200);
  const int embedded = w.addTexture(w.addImageUri("data:image/png;base64," + base64(encodePng(3, 1, glow))));
  const int material = w.addMaterial(MaterialDesc{}
                                         .named("textured")
                                         .withEmission(glm::vec3{1, 1, 1})
                                         .withBaseColorTexture(external)
                                         .withEmissiveTexture(embedded));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, material)})));
  const Scene scene = loadScene(w.write(dir / "textured.gltf"));

  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  ASSERT_EQ(scene.textures.size(), 2u);
  const Material& m = scene.materials[0];
  ASSERT_GE(m.baseColorTexture, 0);
  const Texture& albedo = scene.textures[m.baseColorTexture];
  EXPECT_EQ(albedo.width, 2);
  EXPECT_EQ(albedo.height, 2);
  EXPECT_EQ(albedo.rgba, pixels) << "rows top-down, RGBA as stored";
  ASSERT_GE(m.emissiveTexture, 0);
  EXPECT_EQ(scene.textures[m.emissiveTexture].width, 3);
  EXPECT_EQ(scene.textures[m.emissiveTexture].rgba, glow);
}

TEST(SceneTextures, MissingOrBrokenTextureIsAWarningAndTheFactorRemains) {
  TempDir dir;
  writeTextFile(dir / "garbage.png", "this is not a PNG");
  GltfWriter w;
  const int missing = w.addMaterial(MaterialDesc{}
                                        .named("missing")
                                        .withBaseColor(glm::vec4{0.5f, 0.25f, 1, 1})
                                        .withBaseColorTexture(w.addTexture(w.addImageUri("does_not_exist.png"))));
  const int broken =
      w.addMaterial(MaterialDesc{}.named("broken").withBaseColorTexture(w.addTexture(w.addImageUri("garbage.png"))));
  w.addNode(NodeDesc{}.withMesh(
      w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, missing), box({0, 0, 0}, {1, 1, 1}, broken)})));
  Scene scene;
  ASSERT_NO_THROW(scene = loadScene(w.write(dir / "missing_texture.gltf")));
  EXPECT_TRUE(anyWarningContains(scene, "does_not_exist.png"));
  EXPECT_TRUE(anyWarningContains(scene, "garbage.png"));
  EXPECT_TRUE(scene.textures.empty());
  EXPECT_EQ(scene.materials[0].baseColorTexture, -1);
  EXPECT_EQ(scene.materials[0].baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 1));
  EXPECT_EQ(scene.materials[1].baseColorTexture, -1);
}

TEST(SceneTextures, SharedImageDecodedOnceAndUnusedImagesNotAtAll) {
  TempDir dir;
  const std::vector<std::uint8_t> pixels = checkerPixels();
  GltfWriter w;
  const int image = w.addImageEmbedded(encodePng(2, 2, pixels));  // in the .bin (bufferView)
  const int t0 = w.addTexture(image), t1 = w.addTexture(image);
  // Referenced by no used material: must not even be looked for (no "not found" warning).
  const int unusedTexture = w.addTexture(w.addImageUri("never_loaded.png"));
  const int a = w.addMaterial(MaterialDesc{}.named("a").withBaseColorTexture(t0));
  const int b = w.addMaterial(MaterialDesc{}.named("b").withBaseColorTexture(t1).withEmissiveTexture(t0));
  w.addMaterial(MaterialDesc{}.named("unused").withBaseColorTexture(unusedTexture));
  w.addNode(NodeDesc{}.withMesh(
      w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, a), quad({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, b)})));
  const Scene scene = loadScene(w.write(dir / "shared.gltf"));
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].rgba, pixels);
  EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
  EXPECT_EQ(scene.materials[1].baseColorTexture, 0);
  EXPECT_EQ(scene.materials[1].emissiveTexture, 0);
}

// ------------------------------------------------------------------------------------------------
// .glb, .gltf + .bin and embedded .gltf give the same Scene

void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.texcoords, b.texcoords);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.triangleMaterials, b.triangleMaterials);
  ASSERT_EQ(a.materialRanges.size(), b.materialRanges.size());
  for (size_t i = 0; i < a.materialRanges.size(); ++i) {
    EXPECT_EQ(a.materialRanges[i].material, b.materialRanges[i].material);
    EXPECT_EQ(a.materialRanges[i].firstTriangle, b.materialRanges[i].firstTriangle);
    EXPECT_EQ(a.materialRanges[i].triangleCount, b.materialRanges[i].triangleCount);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].baseColorFactor, b.materials[i].baseColorFactor);
    EXPECT_EQ(a.materials[i].emission, b.materials[i].emission);
    EXPECT_EQ(a.materials[i].baseColorTexture, b.materials[i].baseColorTexture);
    EXPECT_EQ(a.materials[i].emissiveTexture, b.materials[i].emissiveTexture);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) EXPECT_EQ(a.textures[i].rgba, b.textures[i].rgba);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].position, b.lights[i].position);
    EXPECT_EQ(a.lights[i].direction, b.lights[i].direction);
    EXPECT_EQ(a.lights[i].intensity, b.lights[i].intensity);
  }
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].name, b.cameras[i].name);
    EXPECT_EQ(a.cameras[i].position, b.cameras[i].position);
    EXPECT_EQ(a.cameras[i].orientation, b.cameras[i].orientation);
  }
  EXPECT_EQ(a.bounds.min, b.bounds.min);
  EXPECT_EQ(a.bounds.max, b.bounds.max);
  EXPECT_EQ(a.warnings, b.warnings);
}

TEST(SceneFormats, GlbAndEmbeddedGltfLoadTheSameSceneAsGltfWithBin) {
  TempDir dir;
  GltfWriter w;
  const int texture = w.addTexture(w.addImageEmbedded(encodePng(2, 2, checkerPixels())));
  const int m = w.addMaterial(MaterialDesc{}
                                  .named("m")
                                  .withBaseColor(glm::vec4{0.2f, 0.4f, 0.6f, 1})
                                  .withEmission({1, 0.5f, 0}, 4)
                                  .withBaseColorTexture(texture));
  const int mesh = w.addMesh({box({0, 0, 0}, {1, 2, 3}, m), quad({0, 0, 0}, {1, 0, 0}, {0, 0, -1})});
  const int child = w.addNode(NodeDesc{}.withMesh(mesh).rotated(axisAngle(30, glm::normalize(glm::vec3(1, 2, 3)))));
  w.addNode(
      NodeDesc{}.withChildren(std::vector<int>{child}).translated(glm::vec3{1, 2, 3}).scaled(glm::vec3{1, -1, 1}));
  w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.ofType("spot"))).translated(glm::vec3{0, 3, 0}));
  w.addNode(NodeDesc{}.withCamera(w.addCamera(CameraDesc{}.named("cam"))).translated(glm::vec3{0, 0, 9}));
  const Scene gltf = loadScene(w.write(dir / "s.gltf", GltfWriter::Format::Gltf));
  const Scene embedded = loadScene(w.write(dir / "e.gltf", GltfWriter::Format::GltfEmbedded));
  const Scene glb = loadScene(w.write(dir / "s.glb", GltfWriter::Format::Glb));
  EXPECT_EQ(gltf.triangleCount(), 14u);
  EXPECT_EQ(gltf.materials[0].emission, glm::vec3(4, 2, 0)) << "emissive_strength multiplies the factor";
  ASSERT_EQ(gltf.textures.size(), 1u);
  EXPECT_EQ(gltf.textures[0].rgba, checkerPixels());
  EXPECT_NO_FATAL_FAILURE(expectConsistentTriangles(gltf));
  {
    SCOPED_TRACE("embedded");
    expectSameScene(gltf, embedded);
  }
  {
    SCOPED_TRACE("glb");
    expectSameScene(gltf, glb);
  }
}

// ------------------------------------------------------------------------------------------------
// frameBounds

TEST(SceneFrameBounds, AllCornersProjectInsideTheImage) {
  const Bounds boxes[] = {[] {
                            Bounds b;
                            b.extend({-3, -1, -2});
                            b.extend({5, 4, 1});
                            return b;
                          }(),
                          [] {
                            Bounds b;
                            b.extend({0, 0, 0});
                            b.extend({0.556f, 0.5488f, 0.5592f});
                            return b;
                          }(),
                          [] {  // long and flat
                            Bounds b;
                            b.extend({-100, 0, -1});
                            b.extend({100, 0.1f, 1});
                            return b;
                          }()};
  for (const Bounds& bounds : boxes) {
    for (float aspect : {1.0f, 16.0f / 9.0f, 0.5f}) {
      const Camera camera = frameBounds(bounds, aspect);
      EXPECT_NEAR(camera.yfov, glm::radians(45.0f), 1e-6f);
      EXPECT_TRUE(near3(glm::transpose(camera.orientation) * camera.orientation[0], {1, 0, 0}, 1e-5f));
      EXPECT_GT(glm::dot(glm::cross(camera.orientation[0], camera.orientation[1]), camera.orientation[2]), 0.99f);
      EXPECT_LT(camera.orientation[2].y, 0.5f);
      EXPECT_GT(camera.orientation[2].z, 0.8f) << "looks down -z";
      const float tanHalf = std::tan(0.5f * camera.yfov);
      for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                          (corner & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 view = glm::transpose(camera.orientation) * (p - camera.position);
        ASSERT_LT(-view.z, camera.zfar);
        ASSERT_GT(-view.z, camera.znear);
        const float x = view.x / (-view.z * tanHalf * aspect), y = view.y / (-view.z * tanHalf);
        EXPECT_LE(std::abs(x), 1.0f) << "aspect " << aspect << " corner " << corner;
        EXPECT_LE(std::abs(y), 1.0f) << "aspect " << aspect << " corner " << corner;
      }
    }
  }
}

TEST(SceneFrameBounds, EmptyOrPointBoundsGiveAUsableCamera) {
  Bounds point;
  point.extend({1, 2, 3});
  for (const Bounds& b : {Bounds{}, point}) {
    const Camera c = frameBounds(b, 0.0f);
    for (float v : {c.position.x, c.position.y, c.position.z, c.znear, c.zfar, c.aspectRatio})
      EXPECT_TRUE(std::isfinite(v));
    EXPECT_GT(c.znear, 0.0f);
    EXPECT_GT(c.zfar, c.znear);
    const glm::vec3 centre = b.empty() ? glm::vec3(0) : b.center();
    EXPECT_GT(glm::dot(centre - c.position, -c.orientation[2]), c.znear) << "the centre is in front";
  }
}

}  // namespace
}  // namespace lgh::test
