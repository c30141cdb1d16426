// The loader's answers to broken files (render/scene/gltf_loader.cpp and its parts): each must fail
// with a SceneLoadError naming the file and the problem, never a crash, another exception or a read or
// write out of bounds. Truncated .bin, accessors past their buffer view, indices and sparse indices out
// of range, bad .glb headers: the memory-relevant cases, so this file is built only into
// scene_sanitize_tests (AddressSanitizer + UBSan, tests/CMakeLists.txt), which the normal suite runs.
// Loader only: no GL, no engine.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gltf_writer.h"
#include "render/scene/scene.h"

namespace lgh::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Loads `file` expecting SceneLoadError whose message starts with the path and contains every
// keyword; returns the message.
std::string expectLoadError(const fs::path& file, const std::vector<std::string>& keywords) {
  try {
    const Scene scene = loadScene(file);
    ADD_FAILURE() << "expected SceneLoadError for " << file << ", loaded " << scene.triangleCount() << " triangles";
  } catch (const SceneLoadError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string(), 0), 0u) << "message does not start with the path: " << message;
    for (const std::string& k : keywords) EXPECT_TRUE(contains(message, k)) << "no '" << k << "' in: " << message;
    return message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected SceneLoadError, got another exception: " << e.what();
  }
  return {};
}

// ------------------------------------------------------------------------------------------------
// Bad inputs: SceneLoadError naming the file and the problem, never a crash or another exception

GltfWriter oneQuadScene() {
  GltfWriter w;
  const int m = w.addMaterial(MaterialDesc{}.named("white"));
  w.addNode(NodeDesc{}.named("quad node").withMesh(w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m)}, "quad")));
  return w;
}

TEST(SceneErrors, MissingEmptyAndUnreadableFiles) {
  TempDir dir;
  expectLoadError(dir / "no_such_scene.gltf", {"not found"});
  writeTextFile(dir / "empty.gltf", "");
  expectLoadError(dir / "empty.gltf", {"empty"});
  fs::create_directory(dir / "folder.gltf");
  expectLoadError(dir / "folder.gltf", {"directory"});
}

TEST(SceneErrors, BadJson) {
  TempDir dir;
  writeTextFile(dir / "bad.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ { ");
  expectLoadError(dir / "bad.gltf", {"invalid JSON"});
  writeTextFile(dir / "array.gltf", "[1, 2, 3]");
  expectLoadError(dir / "array.gltf", {"JSON"});
}

TEST(SceneErrors, TruncatedBin) {
  TempDir dir;
  const fs::path file = oneQuadScene().write(dir / "truncated.gltf");
  fs::resize_file(dir / "truncated.bin", fs::file_size(dir / "truncated.bin") / 2);
  expectLoadError(file, {"truncated"});
  fs::remove(dir / "truncated.bin");
  expectLoadError(file, {"truncated.bin"});  // the .bin is missing altogether
}

TEST(SceneErrors, AccessorReadingPastItsBufferViewOrBuffer) {
  TempDir dir;
  const GltfWriter w = oneQuadScene();
  json doc = w.json("b.bin");
  doc["accessors"][0]["count"] = 1000;  // POSITION: 4 vertices stored
  writeGltfFiles(dir / "count.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "count.gltf", {"POSITION", "past the end", "'quad'"});

  doc = w.json("b.bin");
  doc["accessors"][0]["byteOffset"] = 8;
  writeGltfFiles(dir / "offset.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "offset.gltf", {"past the end"});

  doc = w.json("b.bin");
  doc["bufferViews"][0]["byteLength"] = 1 << 20;  // the view claims more than the buffer holds
  writeGltfFiles(dir / "view.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "view.gltf", {"bufferView 0", "past the end of buffer"});

  doc = w.json("b.bin");
  doc["accessors"][0]["count"] = 4611686018427387904ull;  // overflow bait
  writeGltfFiles(dir / "huge.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "huge.gltf", {"past the end"});

  doc = w.json("b.bin");
  doc["accessors"][1]["count"] = 3;  // NORMAL shorter than POSITION
  writeGltfFiles(dir / "normals.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "normals.gltf", {"NORMAL", "3 elements"});

  doc = w.json("b.bin");
  doc["accessors"][0]["type"] = "VEC2";
  writeGltfFiles(dir / "type.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "type.gltf", {"POSITION", "VEC2", "VEC3 FLOAT"});
}

TEST(SceneErrors, IndexOutOfRange) {
  TempDir dir;
  GltfWriter w;
  PrimitiveDesc p = quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  p.indices[4] = 99;
  w.addNode(NodeDesc{}.withMesh(w.addMesh({p}, "holey")));
  expectLoadError(w.write(dir / "index.gltf"), {"index 99", "out of range", "4 vertices", "'holey'"});
}

TEST(SceneErrors, NonFinitePositionsNameMeshAndPrimitive) {
  TempDir dir;
  for (float bad : {std::nanf(""), INFINITY}) {
    GltfWriter w;
    PrimitiveDesc p = quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    p.positions[2].y = bad;
    w.addNode(NodeDesc{}.withMesh(w.addMesh({box({0, 0, 0}, {1, 1, 1}), p}, "spiky")));
    expectLoadError(w.write(dir / "nan.gltf"), {"NaN", "mesh 0 'spiky' primitive 1", "vertex 2"});
  }
}

TEST(SceneErrors, UnknownRequiredExtension) {
  TempDir dir;
  GltfWriter w = oneQuadScene();
  w.requireExtension("KHR_lights_punctual");  // supported: fine
  EXPECT_NO_THROW(loadScene(w.write(dir / "ok.gltf")));
  w.requireExtension("KHR_draco_mesh_compression");
  expectLoadError(w.write(dir / "draco.gltf"),
                  {"KHR_draco_mesh_compression", "KHR_lights_punctual", "KHR_materials_emissive_strength"});
}

TEST(SceneErrors, ZeroTriangles) {
  TempDir dir;
  GltfWriter w;
  PrimitiveDesc points;
  points.positions = {{0, 0, 0}, {1, 0, 0}};
  points.mode = gltf::kPoints;
  w.addNode(NodeDesc{}.withMesh(w.addMesh({points})));
  w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{})));
  expectLoadError(w.write(dir / "points_only.gltf"), {"no triangles"});
  GltfWriter empty;
  empty.addNode(NodeDesc{}.named("lonely"));
  expectLoadError(empty.write(dir / "nothing.gltf"), {"no triangles"});
}

TEST(SceneErrors, GlbWithBadHeader) {
  TempDir dir;
  const fs::path good = oneQuadScene().write(dir / "good.glb", GltfWriter::Format::Glb);
  EXPECT_NO_THROW(loadScene(good));
  std::vector<char> bytes(fs::file_size(good));
  std::ifstream(good, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
  auto writeVariant = [&](const std::string& name, std::vector<char> b) {
    std::ofstream(dir / name, std::ios::binary).write(b.data(), std::streamsize(b.size()));
    return dir / name;
  };
  std::vector<char> magic = bytes;
  magic[0] = 'x';
  expectLoadError(writeVariant("magic.glb", magic), {".glb", "magic"});
  std::vector<char> version = bytes;
  version[4] = 1;
  expectLoadError(writeVariant("version.glb", version), {".glb", "version"});
  std::vector<char> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(bytes.size() - 40));
  expectLoadError(writeVariant("cut.glb", cut), {".glb", "truncated"});
  std::vector<char> chunk = bytes;
  chunk[12] = char(0xFF);  // JSON chunk longer than the file
  chunk[13] = char(0xFF);
  expectLoadError(writeVariant("chunk.glb", chunk), {".glb", "JSON chunk"});
  expectLoadError(writeVariant("tiny.glb", {'g', 'l', 'T', 'F', 2}), {".glb", "header"});
}

TEST(SceneErrors, NodeHierarchyCyclesAndSharedChildren) {
  TempDir dir;
  const GltfWriter w = oneQuadScene();
  json doc = w.json("b.bin");
  doc["nodes"].push_back({{"name", "a"}, {"children", {2}}});
  doc["nodes"].push_back({{"name", "b"}, {"children", {1}}});
  writeGltfFiles(dir / "cycle.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "cycle.gltf", {"cycle"});

  doc = w.json("b.bin");
  doc["nodes"][0]["children"] = {0};
  writeGltfFiles(dir / "self.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "self.gltf", {"cycle", "node 0 'quad node'"});

  doc = w.json("b.bin");
  doc["nodes"].push_back({{"children", {0}}});
  doc["nodes"].push_back({{"children", {0}}});
  doc["scenes"][0]["nodes"] = {1, 2};
  writeGltfFiles(dir / "shared_child.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "shared_child.gltf", {"not a tree"});

  doc = w.json("b.bin");
  doc["nodes"][0]["children"] = {42};
  writeGltfFiles(dir / "child.gltf", doc, w.binary(), "b.bin");
  expectLoadError(dir / "child.gltf", {"child 42"});
}

TEST(SceneErrors, LightCameraMeshAndMaterialIndicesOutOfRange) {
  TempDir dir;
  const GltfWriter w = oneQuadScene();
  auto variant = [&](const std::string& name, auto edit) {
    json doc = w.json("b.bin");
    edit(doc);
    writeGltfFiles(dir / name, doc, w.binary(), "b.bin");
    return dir / name;
  };
  expectLoadError(
      variant("light.gltf", [](json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 5; }),
      {"light 5", "0 KHR_lights_punctual lights"});
  expectLoadError(variant("camera.gltf", [](json& d) { d["nodes"][0]["camera"] = 3; }), {"camera 3"});
  expectLoadError(variant("mesh.gltf", [](json& d) { d["nodes"][0]["mesh"] = 9; }), {"mesh 9"});
  expectLoadError(variant("material.gltf", [](json& d) { d["meshes"][0]["primitives"][0]["material"] = 4; }),
                  {"material 4"});
  expectLoadError(
      variant("accessor.gltf", [](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 77; }),
      {"accessor 77"});
  expectLoadError(variant("texture.gltf",
                          [](json& d) {
                            d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 6}};
                          }),
                  {"texture 6"});
  expectLoadError(variant("scene.gltf", [](json& d) { d["scene"] = 2; }), {"scene"});
  expectLoadError(variant("spot.gltf",
                          [](json& d) {
                            d["extensions"]["KHR_lights_punctual"]["lights"] = {
                                {{"type", "spot"}, {"spot", {{"innerConeAngle", 1.0}, {"outerConeAngle", 0.5}}}}};
                            d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
                          }),
                  {"cone"});
}

// ------------------------------------------------------------------------------------------------
// Sparse accessors: the substitution lands; an index past the accessor's count is refused, never written

TEST(SceneMeshes, SparseAccessorOverridesBaseValues) {
  TempDir dir;
  GltfWriter w;
  const int mesh = w.addMesh({quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0})});
  w.addNode(NodeDesc{}.withMesh(mesh));
  // Move vertex 2 to (1, 1, 0.5) through a sparse substitution on the POSITION accessor.
  const std::uint16_t sparseIndex = 2;
  const float sparseValue[3] = {1.0f, 1.0f, 0.5f};
  const int indexView = w.addBufferView(&sparseIndex, 2);
  const int valueView = w.addBufferView(sparseValue, 12);
  json doc = w.json("sparse.bin");
  doc["accessors"][0]["sparse"] = {{"count", 1},
                                   {"indices", {{"bufferView", indexView}, {"componentType", gltf::kUnsignedShort}}},
                                   {"values", {{"bufferView", valueView}}}};
  doc["accessors"][0]["max"] = {1.0, 1.0, 0.5};
  writeGltfFiles(dir / "sparse.gltf", doc, w.binary(), "sparse.bin");
  const Scene scene = loadScene(dir / "sparse.gltf");
  bool moved = false;
  for (const glm::vec3& p : scene.positions) moved |= p == glm::vec3(1.0f, 1.0f, 0.5f);
  EXPECT_TRUE(moved);

  // A sparse index past the accessor's count is an error, not a write out of bounds.
  GltfWriter bad = w;
  const std::uint16_t badIndex = 7;
  const int badView = bad.addBufferView(&badIndex, 2);
  json badDoc = bad.json("sparse_bad.bin");
  badDoc["accessors"][0]["sparse"] = doc["accessors"][0]["sparse"];
  badDoc["accessors"][0]["sparse"]["indices"]["bufferView"] = badView;
  writeGltfFiles(dir / "sparse_bad.gltf", badDoc, bad.binary(), "sparse_bad.bin");
  expectLoadError(dir / "sparse_bad.gltf", {"sparse index 7", "out of range"});
}

}  // namespace
}  // namespace lgh::test
