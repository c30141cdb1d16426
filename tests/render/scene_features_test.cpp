// Loading what real scenes use (issue 14), checked on the loaded Scene without GL: the scene origin
// that keeps far-away scenes exact, alphaMode / alphaCutoff / doubleSided, COLOR_0, TEXCOORD_1,
// KHR_texture_transform, KHR_mesh_quantization, and the command-line lights (--sun, --point).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

#include "gltf_writer.h"
#include "render/scene/added_lights.h"
#include "render/scene/scene.h"
#include "shared/material_eval.h"

namespace lgh::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::filesystem::path writeTranslatedBox(const TempDir& dir, const std::string& name, const glm::dvec3& offset) {
  GltfWriter w;
  const int mesh = w.addMesh({box({0.25f, 0.5f, -0.125f}, {0.5f, 0.5f, 0.5f})});
  const int body = w.addNode(NodeDesc{}.withMesh(mesh));
  const int lamp = w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{})).translated({0, 3, 0}));
  const int eye = w.addNode(NodeDesc{}.withCamera(w.addCamera(CameraDesc{})).translated({0, 1, 4}));
  w.addNode(NodeDesc{}.translated(offset).withChildren({body, lamp, eye}));
  return w.write(dir / (name + ".gltf"));
}

TEST(SceneOrigin, FarAwaySceneKeepsItsPrecisionInSceneSpace) {
  TempDir dir;
  const Scene reference = loadScene(writeTranslatedBox(dir, "origin", glm::dvec3(0.0)));
  // Near the world origin, scene space is world space (the users' coordinates in AOVs and the viewer).
  EXPECT_EQ(reference.origin, glm::dvec3(0.0));
  const double grid = 2.0;  // the power of two above the box's diagonal (1.73)
  for (double distance : {1e3, 1e5, 1e6, 1e9}) {
    const glm::dvec3 offset(distance + 0.3, -0.5 * distance, 0.25 * distance);
    const Scene far = loadScene(writeTranslatedBox(dir, "far", offset));
    // The origin lies on the grid, within half a cell of the geometry's centre.
    const glm::dvec3 fromCentre = far.origin - (offset + glm::dvec3(0.25, 0.5, -0.125));
    EXPECT_LE(std::max({std::abs(fromCentre.x), std::abs(fromCentre.y), std::abs(fromCentre.z)}), 0.5 * grid)
        << distance;
    EXPECT_EQ(glm::fract(far.origin / grid), glm::dvec3(0.0)) << distance;
    ASSERT_EQ(far.positions.size(), reference.positions.size());
    // World positions rebuilt in double agree with the translated originals to float rounding of
    // scene-space values (a few units here), not of world values (0.06 at 1e6, 64 at 1e9).
    const auto expectSamePoint = [&](const glm::vec3& scenePoint, const glm::vec3& original, const char* what) {
      const glm::dvec3 world = glm::dvec3(scenePoint) + far.origin, expected = glm::dvec3(original) + offset;
      EXPECT_LE(glm::length(world - expected), 1e-6 + 1e-12 * distance) << what << " at " << distance;
    };
    for (size_t i = 0; i < far.positions.size(); ++i)
      expectSamePoint(far.positions[i], reference.positions[i], "vertex");
    expectSamePoint(far.lights[0].position, reference.lights[0].position, "light");
    expectSamePoint(far.cameras[0].position, reference.cameras[0].position, "camera");
    EXPECT_LE(glm::length(glm::dvec3(far.bounds.center()) + far.origin - offset - glm::dvec3(0.25, 0.5, -0.125)), 1e-6);
  }
}

TEST(SceneMaterials, AlphaModeCutoffAndDoubleSided) {
  TempDir dir;
  GltfWriter w;
  const int opaque = w.addMaterial(MaterialDesc{});
  const int mask = w.addMaterial(MaterialDesc{}.withAlphaMask(0.3).twoSided());
  MaterialDesc defaultCutoff;
  defaultCutoff.alphaMode = "MASK";
  const int maskDefault = w.addMaterial(defaultCutoff);
  MaterialDesc blendDesc;
  blendDesc.alphaMode = "BLEND";
  const int blend = w.addMaterial(blendDesc.named("glass"));
  std::vector<PrimitiveDesc> prims;
  for (int m : {opaque, mask, maskDefault, blend}) prims.push_back(quad({float(m), 0, 0}, {1, 0, 0}, {0, 1, 0}, m));
  w.addNode(NodeDesc{}.withMesh(w.addMesh(prims)));
  const Scene scene = loadScene(w.write(dir / "alpha.gltf"));
  EXPECT_EQ(scene.materials[opaque].alphaMode, AlphaMode::Opaque);
  EXPECT_FALSE(scene.materials[opaque].doubleSided);
  EXPECT_EQ(scene.materials[mask].alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(scene.materials[mask].alphaCutoff, 0.3f);
  EXPECT_TRUE(scene.materials[mask].doubleSided);
  EXPECT_FLOAT_EQ(scene.materials[maskDefault].alphaCutoff, 0.5f);  // glTF's default
  EXPECT_EQ(scene.materials[blend].alphaMode, AlphaMode::Blend);
  bool warned = false;
  for (const std::string& warning : scene.warnings)
    warned |= warning.find("BLEND") != std::string::npos && warning.find("glass") != std::string::npos;
  EXPECT_TRUE(warned) << "BLEND is rendered opaque: the user must be told";
}

TEST(SceneMaterials, AlphaTestUsesFactorTextureAndVertexAlpha) {
  // material_eval.h is compiled as C++ here and as GLSL in the G-buffer and the BVH traversal.
  gpu::GpuMaterial m{};
  m.baseColorFactor = glm::vec4(1, 1, 1, 0.8f);
  m.alphaCutoff = 0.5f;
  EXPECT_FALSE(gpu::alphaCutOut(m, 1.0f, 1.0f));    // 0.8
  EXPECT_TRUE(gpu::alphaCutOut(m, 0.5f, 1.0f));     // 0.4: the texture's alpha counts
  EXPECT_TRUE(gpu::alphaCutOut(m, 1.0f, 0.6f));     // 0.48: COLOR_0's alpha counts
  EXPECT_FALSE(gpu::alphaCutOut(m, 0.625f, 1.0f));  // exactly 0.5 stays (alpha >= cutoff is opaque)
  m.alphaCutoff = -1.0f;                            // OPAQUE and BLEND: never cut
  EXPECT_FALSE(gpu::alphaCutOut(m, 0.0f, 0.0f));
}

TEST(SceneMaterials, TextureTransformMatchesTheExtensionsDefinition) {
  TempDir dir;
  GltfWriter w;
  const int texture = w.addTexture(w.addImageEmbedded(encodePng(1, 1, {255, 255, 255, 255})));
  const double rotation = 0.3;
  const int m = w.addMaterial(MaterialDesc{}.withBaseColorTexture(texture).withBaseColorTransform(
      {{"offset", {0.25, -0.5}}, {"rotation", rotation}, {"scale", {2.0, 3.0}}, {"texCoord", 1}}));
  PrimitiveDesc q = quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m);
  q.texcoords1 = q.texcoords;
  w.addNode(NodeDesc{}.withMesh(w.addMesh({q})));
  const Scene scene = loadScene(w.write(dir / "transform.gltf"));
  const Material& material = scene.materials[m];
  EXPECT_EQ(material.baseColorTexCoord, 1) << "KHR_texture_transform.texCoord overrides textureInfo.texCoord";
  // translation * rotation * scale, rotation matrix columns (cos, sin), (-sin, cos) as the extension's GLSL.
  const auto expected = [&](double u, double v) {
    const double su = 2.0 * u, sv = 3.0 * v;
    return glm::dvec2(std::cos(rotation) * su - std::sin(rotation) * sv + 0.25,
                      std::sin(rotation) * su + std::cos(rotation) * sv - 0.5);
  };
  for (const glm::dvec2 uv : {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(0.3, 0.7)}) {
    const glm::vec3 got = material.baseColorUvTransform * glm::vec3(glm::vec2(uv), 1.0f);
    EXPECT_NEAR(got.x, expected(uv.x, uv.y).x, 1e-6);
    EXPECT_NEAR(got.y, expected(uv.x, uv.y).y, 1e-6);
  }
}

TEST(SceneMeshes, VertexColoursAndSecondTexcoordsAreLoaded) {
  TempDir dir;
  GltfWriter w;
  PrimitiveDesc q = quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  q.colors = {{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 1}, {1, 1, 1, 0}};
  q.texcoords1 = {{0.5f, 0.5f}, {0.25f, 0.5f}, {0.75f, 0.5f}, {0.5f, 0.125f}};
  PrimitiveDesc plain = quad({2, 0, 0}, {1, 0, 0}, {0, 1, 0});
  w.addNode(NodeDesc{}.withMesh(w.addMesh({q, plain})));
  const Scene scene = loadScene(w.write(dir / "colours.gltf"));
  ASSERT_EQ(scene.colors.size(), scene.positions.size());
  ASSERT_EQ(scene.texcoords1.size(), scene.positions.size());
  size_t matched = 0;
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    const glm::vec3 p = scene.positions[i] + glm::vec3(scene.origin);
    for (size_t k = 0; k < 4; ++k)
      if (glm::length(p - q.positions[k]) < 1e-6f) {
        EXPECT_EQ(scene.colors[i], q.colors[k]);
        EXPECT_EQ(scene.texcoords1[i], q.texcoords1[k]);
        ++matched;
      }
    if (p.x > 1.5f) {
      EXPECT_EQ(scene.colors[i], glm::vec4(1.0f)) << "no COLOR_0: white";
    }
  }
  EXPECT_EQ(matched, 4u);
}

TEST(SceneMeshes, QuantizedAttributesDequantizeLikeTheFloatOnes) {
  TempDir dir;
  const auto write = [&](const std::string& name, bool quantized, bool normalized) {
    GltfWriter w;
    PrimitiveDesc b = box({0.1f, 0.2f, -0.3f}, {0.5f, 0.25f, 0.4f});
    float scale = 1.0f;
    if (quantized) {
      b.positionType = gltf::kShort;
      b.positionNormalized = normalized;
      b.normalType = gltf::kByte;
      scale = normalized ? 1.0f : 1.0f / 1024.0f;  // unnormalized: integer positions dequantized by the node
      if (!normalized)
        for (glm::vec3& p : b.positions) p *= 1024.0f;
    }
    w.addNode(NodeDesc{}.withMesh(w.addMesh({b})).scaled(glm::vec3(scale)));
    return loadScene(w.write(dir / (name + ".gltf")));
  };
  const Scene reference = write("float", false, false);
  for (bool normalized : {true, false}) {
    const Scene q = write(normalized ? "normalized" : "integer", true, normalized);
    ASSERT_EQ(q.positions.size(), reference.positions.size());
    const double step = normalized ? 1.0 / 32767.0 : 1.0 / 1024.0;
    for (size_t i = 0; i < q.positions.size(); ++i) {
      EXPECT_LE(
          glm::length(glm::dvec3(q.positions[i]) + q.origin - glm::dvec3(reference.positions[i]) - reference.origin),
          step);
      EXPECT_LE(glm::length(q.normals[i] - reference.normals[i]), 1e-6f);  // axis-aligned: exact in BYTE
    }
  }
}

TEST(AddedLights, SunFollowsAzimuthAndElevation) {
  const PunctualLight sun = parseSunOption("30,45");
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_EQ(sun.intensity, glm::vec3(kDefaultSunLux));
  // Towards the sun: 45 degrees up, 30 degrees from +Z towards +X.
  const glm::vec3 towards = -sun.direction;
  EXPECT_NEAR(towards.y, std::sin(kPi / 4), 1e-6);
  EXPECT_NEAR(std::atan2(towards.x, towards.z), kPi / 6, 1e-6);
  EXPECT_NEAR(glm::length(towards), 1.0f, 1e-6f);
  const glm::vec2 angles = sunAngles(towards);
  EXPECT_NEAR(angles.x, 30.0f, 1e-4f);
  EXPECT_NEAR(angles.y, 45.0f, 1e-4f);
  EXPECT_EQ(parseSunOption("-90,90,3.5").intensity, glm::vec3(3.5f));
  EXPECT_NEAR(parseSunOption("0,90").direction.y, -1.0f, 1e-6f);  // noon: straight down
  for (const char* bad : {"30", "30,45,1,2", "30,91", "a,45", "30,45,-1", "30,", "30,45,1e39"})
    EXPECT_THROW(parseSunOption(bad), std::invalid_argument) << bad;
}

TEST(AddedLights, PointIsInWorldCoordinatesAndColoured) {
  Scene scene;
  scene.origin = glm::dvec3(1e6, -2e5, 3.0);
  const PunctualLight point = parsePointOption("1000001.5,-199998,3.25,40,1,0.5,0", scene);
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_EQ(point.position, glm::vec3(1.5f, 2.0f, 0.25f));
  EXPECT_EQ(point.intensity, glm::vec3(40.0f, 20.0f, 0.0f));
  EXPECT_EQ(parsePointOption("0,0,0,2", Scene{}).intensity, glm::vec3(2.0f));
  for (const char* bad : {"0,0,0", "0,0,0,1,1", "0,0,0,-1", "0,0,0,1,1,-1,1", "x,0,0,1"})
    EXPECT_THROW(parsePointOption(bad, scene), std::invalid_argument) << bad;
  addCommandLineLights(scene, {"10,20"}, {"1000000,-200000,3,1"});
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[1].position, glm::vec3(0.0f));
}

TEST(AddedLights, SceneHasLightCountsPunctualAndEmissiveInUse) {
  Scene scene;
  scene.materials.push_back(Material{});
  scene.materialRanges.push_back({0, 0, 1});
  EXPECT_FALSE(sceneHasLight(scene));
  scene.materials[0].emission = glm::vec3(1.0f);
  EXPECT_TRUE(sceneHasLight(scene));
  scene.materials[0].emission = glm::vec3(0.0f);
  scene.lights.push_back(parseSunOption("0,45"));
  EXPECT_TRUE(sceneHasLight(scene));
  EXPECT_NE(noLightHint().find("--sun AZIMUTH,ELEVATION[,LUX]"), std::string::npos);
  EXPECT_NE(noLightHint().find("--point X,Y,Z,INTENSITY[,R,G,B]"), std::string::npos);
}

}  // namespace
}  // namespace lgh::test
