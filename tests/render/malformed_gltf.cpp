#include "malformed_gltf.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "gltf_writer.h"

namespace lgh::test {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A small valid scene (a lit, textured quad seen by a camera): each case breaks one thing in it.
struct BaseScene {
  GltfWriter writer;
  BaseScene() {
    PrimitiveDesc q = quad({-1, 0, -1}, {2, 0, 0}, {0, 0, 2}, 0);
    q.normals.assign(q.positions.size(), glm::vec3(0, -1, 0));
    q.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    writer.addMaterial(MaterialDesc{}.named("grey").withBaseColor({0.5f, 0.5f, 0.5f, 1.0f}));
    writer.addNode(NodeDesc{}.named("floor").withMesh(writer.addMesh({q}, "floor")));
    writer.addNode(
        NodeDesc{}.named("eye").withCamera(writer.addCamera(CameraDesc{}.named("eye"))).translated({0, 1, 4}));
    writer.addNode(
        NodeDesc{}.named("lamp").withLight(writer.addLight(LightDesc{}.withIntensity(10))).translated({0, 2, 0}));
  }
};

// The base scene's animation: the lamp (node 2) carried along x in one second.
void animatedLamp(GltfWriter& w) { w.addAnimationChannel(2, "translation", {0, 1}, {0, 2, 0, 1, 2, 0}); }

// Writes the base scene with `edit` applied to its JSON (and to its binary buffer).
std::function<fs::path(const fs::path&)> edited(const std::string& name,
                                                std::function<void(Json&, std::vector<std::uint8_t>&)> edit,
                                                std::function<void(GltfWriter&)> build = nullptr) {
  return [=](const fs::path& dir) {
    BaseScene base;
    if (build) build(base.writer);
    Json doc = base.writer.json(name + ".bin");
    std::vector<std::uint8_t> bin = base.writer.binary();
    edit(doc, bin);
    doc["buffers"][0]["byteLength"] = bin.size();
    const fs::path file = dir / (name + ".gltf");
    writeGltfFiles(file, doc, bin, name + ".bin");
    return file;
  };
}

// The accessor of attribute `attribute` of the first primitive of mesh 0.
Json& attributeAccessor(Json& doc, const char* attribute) {
  return doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"][attribute].get<int>()];
}

// Overwrites float `index` of the data of accessor `accessor` (tightly packed floats) with `value`.
void poke(Json& doc, std::vector<std::uint8_t>& bin, int accessor, size_t index, float value) {
  const Json& a = doc["accessors"][accessor];
  const Json& view = doc["bufferViews"][a["bufferView"].get<int>()];
  const size_t offset = view["byteOffset"].get<size_t>() + a.value("byteOffset", size_t(0)) + 4 * index;
  std::memcpy(&bin[offset], &value, 4);
}

std::vector<MalformedGltf> makeCases() {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<MalformedGltf> cases;
  const auto add = [&](std::string name, std::string rule, std::function<void(Json&, std::vector<std::uint8_t>&)> edit,
                       std::vector<std::string> words, std::function<void(GltfWriter&)> build = nullptr) {
    cases.push_back({name, rule, edited(name, std::move(edit), std::move(build)), std::move(words)});
  };

  add("AssetVersion1", "UNKNOWN_ASSET_MAJOR_VERSION", [](Json& d, auto&) { d["asset"]["version"] = "1.0"; },
      {"asset.version", "1.0", "not a glTF 2.0 file"});
  add("AssetVersion3", "UNKNOWN_ASSET_MAJOR_VERSION", [](Json& d, auto&) { d["asset"]["version"] = "3.0"; },
      {"asset.version", "3.0", "major version 2"});
  add("AssetVersionMalformed", "PATTERN_MISMATCH", [](Json& d, auto&) { d["asset"]["version"] = "two"; },
      {"asset.version", "'two'", "MAJOR.MINOR"});
  add("AssetVersionMissing", "UNDEFINED_PROPERTY (asset.version)", [](Json& d, auto&) { d["asset"].erase("version"); },
      {"asset.version is missing"});
  add("PositionShortWithoutQuantization", "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT",
      [](Json& d, auto&) { attributeAccessor(d, "POSITION")["componentType"] = 5122; },  // SHORT over the float data
      {"POSITION", "SHORT", "KHR_mesh_quantization"});
  add("PositionVec2", "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT",
      [](Json& d, auto&) { attributeAccessor(d, "POSITION")["type"] = "VEC2"; }, {"POSITION", "VEC2", "VEC3 FLOAT"});
  add("NormalUnsignedByte", "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT",
      [](Json& d, auto&) {
        Json& a = attributeAccessor(d, "NORMAL");
        a["componentType"] = 5121;
        a["normalized"] = true;
      },
      {"NORMAL", "UNSIGNED_BYTE", "VEC3 FLOAT"});
  add("TexcoordShortWithoutQuantization", "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT",
      [](Json& d, auto&) { attributeAccessor(d, "TEXCOORD_0")["componentType"] = 5122; },
      {"TEXCOORD_0", "SHORT", "VEC2 FLOAT"});
  add("NormalizedFloat", "ACCESSOR_NORMALIZED_INVALID",
      [](Json& d, auto&) { attributeAccessor(d, "TEXCOORD_0")["normalized"] = true; },
      {"TEXCOORD_0", "normalized", "FLOAT"});
  add("NanNormal", "ACCESSOR_INVALID_FLOAT",
      [=](Json& d, auto& bin) {
        poke(d, bin, d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>(), 4, nan);
      },
      {"NORMAL", "vertex 1", "NaN"});
  add("NanTexcoord", "ACCESSOR_INVALID_FLOAT",
      [=](Json& d, auto& bin) {
        poke(d, bin, d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].get<int>(), 5, nan);
      },
      {"TEXCOORD_0", "vertex 2", "NaN"});
  add("TranslationOverflowsFloat", "non-finite float (1e39)",
      [](Json& d, auto&) {
        d["nodes"][0]["translation"] = {1e39, 0, 0};
      },
      {"node 0 'floor'", "1e+39", "not a finite float"});
  add("LightIntensityOverflowsFloat", "non-finite float (1e39)",
      [](Json& d, auto&) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 1e39; },
      {"light 0", "non-finite"});
  add("LightRangeNegative", "VALUE_NOT_IN_RANGE (light.range > 0)",
      [](Json& d, auto&) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["range"] = -2.0; },
      {"light 0", "range", "-2"});
  add("CameraZfarNotBeyondZnear", "CAMERA_ZFAR_LEQUAL_ZNEAR",
      [](Json& d, auto&) { d["cameras"][0]["perspective"]["zfar"] = 0.005; }, {"camera 0 'eye'", "zfar", "znear"});
  add("CameraZnearOverflowsFloat", "non-finite float (1e39)",
      [](Json& d, auto&) {
        d["cameras"][0]["perspective"]["znear"] = 1e39;
        d["cameras"][0]["perspective"]["zfar"] = 1e40;
      },
      {"camera 0 'eye'", "znear", "1e+39"});
  add("MatrixAndTrs", "NODE_MATRIX_TRS",
      [](Json& d, auto&) {
        d["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        d["nodes"][0]["translation"] = {0, 0, 1};
      },
      {"node 0 'floor'", "both a matrix and translation"});
  add("ProjectiveMatrix", "NODE_MATRIX_NON_TRS",
      [](Json& d, auto&) {
        d["nodes"][0].erase("translation");
        d["nodes"][0]["matrix"] = {1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      },
      {"node 0 'floor'", "(0, 0, 0, 1)"});
  add("BaseColorFactorAboveOne", "VALUE_NOT_IN_RANGE (baseColorFactor in [0, 1])",
      [](Json& d, auto&) {
        d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {2.0, 0.5, 0.5, 1.0};
      },
      {"material 0 'grey'", "baseColorFactor", "outside [0, 1]"});
  add("UnknownAlphaMode", "VALUE_NOT_IN_LIST (alphaMode)",
      [](Json& d, auto&) { d["materials"][0]["alphaMode"] = "CUTOUT"; },
      {"material 0 'grey'", "alphaMode 'CUTOUT'", "MASK"});
  add("NegativeAlphaCutoff", "VALUE_NOT_IN_RANGE (alphaCutoff >= 0)",
      [](Json& d, auto&) {
        d["materials"][0]["alphaMode"] = "MASK";
        d["materials"][0]["alphaCutoff"] = -0.5;
      },
      {"material 0 'grey'", "alphaCutoff", "-0.5"});
  add("TextureNeedsMissingTexcoord1", "MESH_PRIMITIVE_TOO_FEW_TEXCOORDS",
      [](Json& d, auto&) {
        d["images"] = {{{"uri", "white.png"}}};
        d["textures"] = {{{"source", 0}}};
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}, {"texCoord", 1}};
      },
      {"mesh 0 'floor' primitive 0", "TEXCOORD_1", "does not have"});
  add("TextureTransformOverflowsFloat", "non-finite float (1e39)",
      [](Json& d, auto&) {
        d["images"] = {{{"uri", "white.png"}}};
        d["textures"] = {{{"source", 0}}};
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {
            {"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {1e39, 1.0}}}}}}};
        d["extensionsUsed"].push_back("KHR_texture_transform");
      },
      {"material 0 'grey'", "KHR_texture_transform", "1e+39"});
  add("IndicesWithByteStride", "MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE",
      [](Json& d, auto&) {
        const int indices = d["meshes"][0]["primitives"][0]["indices"].get<int>();
        d["bufferViews"][d["accessors"][indices]["bufferView"].get<int>()]["byteStride"] = 4;
      },
      {"indices", "byteStride"});
  add("SparseIndicesNotIncreasing", "ACCESSOR_SPARSE_INDICES_NON_INCREASING",
      [](Json& d, auto& bin) {
        // Two substitutions of TEXCOORD_0 at indices 2, 1: order matters when they repeat, so glTF forbids it.
        const size_t at = bin.size();
        for (std::uint32_t i : {2u, 1u})
          bin.insert(bin.end(), reinterpret_cast<std::uint8_t*>(&i), reinterpret_cast<std::uint8_t*>(&i) + 4);
        for (float v : {0.f, 0.f, 0.f, 0.f})
          bin.insert(bin.end(), reinterpret_cast<std::uint8_t*>(&v), reinterpret_cast<std::uint8_t*>(&v) + 4);
        const int views = int(d["bufferViews"].size());
        d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 8}});
        d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 8}, {"byteLength", 16}});
        attributeAccessor(d, "TEXCOORD_0")["sparse"] = {{"count", 2},
                                                        {"indices", {{"bufferView", views}, {"componentType", 5125}}},
                                                        {"values", {{"bufferView", views + 1}}}};
      },
      {"TEXCOORD_0", "sparse indices are not strictly increasing"});
  add("SparseCountAboveCount", "ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE",
      [](Json& d, auto& bin) {
        const size_t at = bin.size();
        for (std::uint32_t i = 0; i < 5; ++i)
          bin.insert(bin.end(), reinterpret_cast<std::uint8_t*>(&i), reinterpret_cast<std::uint8_t*>(&i) + 4);
        bin.insert(bin.end(), 40, 0);
        const int views = int(d["bufferViews"].size());
        d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 20}});
        d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 20}, {"byteLength", 40}});
        attributeAccessor(d, "TEXCOORD_0")["sparse"] = {{"count", 5},
                                                        {"indices", {{"bufferView", views}, {"componentType", 5125}}},
                                                        {"values", {{"bufferView", views + 1}}}};
      },
      {"TEXCOORD_0", "overrides 5 elements", "accessor's 4"});
  add("EmissiveFactorAboveOne", "VALUE_NOT_IN_RANGE (emissiveFactor in [0, 1])",
      [](Json& d, auto&) {
        d["materials"][0]["emissiveFactor"] = {5.0, 0.0, 0.0};
      },
      {"material 0 'grey'", "emissiveFactor", "outside [0, 1]"});

  // Animations: the lamp (node 2) carried along x in one second, each case breaking one rule.
  const auto animation = [](Json& d) -> Json& { return d["animations"][0]; };
  const auto addAnimated = [&](std::string name, std::string rule,
                               std::function<void(Json&, std::vector<std::uint8_t>&)> edit,
                               std::vector<std::string> words) {
    add(std::move(name), std::move(rule), std::move(edit), std::move(words), animatedLamp);
  };
  addAnimated("AnimationSamplerOutOfRange", "UNRESOLVED_REFERENCE (animation.channels.sampler)",
              [=](Json& d, auto&) { animation(d)["channels"][0]["sampler"] = 5; },
              {"animation 0 channel 0", "sampler 5", "1 samplers"});
  addAnimated("AnimationNodeOutOfRange", "UNRESOLVED_REFERENCE (animation.channels.target.node)",
              [=](Json& d, auto&) { animation(d)["channels"][0]["target"]["node"] = 9; },
              {"animation 0 channel 0", "node 9", "3 nodes"});
  addAnimated("AnimationUnknownPath", "VALUE_NOT_IN_LIST (animation.channels.target.path)",
              [=](Json& d, auto&) { animation(d)["channels"][0]["target"]["path"] = "position"; },
              {"animation 0 channel 0", "'position'"});
  addAnimated("AnimationUnknownInterpolation", "VALUE_NOT_IN_LIST (animation.samplers.interpolation)",
              [=](Json& d, auto&) { animation(d)["samplers"][0]["interpolation"] = "SMOOTH"; },
              {"animation 0 channel 0 sampler 0", "'SMOOTH'"});
  addAnimated("AnimationTimesNotIncreasing", "ANIMATION_SAMPLER_INPUT_ACCESSOR_NON_INCREASING",
              [=](Json& d, auto& bin) { poke(d, bin, animation(d)["samplers"][0]["input"].get<int>(), 1, 0.0f); },
              {"animation 0 channel 0 sampler 0", "not strictly increasing", "time 1"});
  addAnimated("AnimationTimeNan", "ACCESSOR_INVALID_FLOAT",
              [=](Json& d, auto& bin) { poke(d, bin, animation(d)["samplers"][0]["input"].get<int>(), 0, nan); },
              {"animation 0 channel 0 sampler 0", "time 0", "NaN"});
  addAnimated("AnimationKeyNan", "ACCESSOR_INVALID_FLOAT",
              [=](Json& d, auto& bin) { poke(d, bin, animation(d)["samplers"][0]["output"].get<int>(), 4, nan); },
              {"animation 0 channel 0 sampler 0", "output value 1", "NaN"});
  addAnimated(
      "AnimationInputNotFloat", "ANIMATION_SAMPLER_INPUT_ACCESSOR_INVALID_FORMAT",
      [=](Json& d, auto&) { d["accessors"][animation(d)["samplers"][0]["input"].get<int>()]["componentType"] = 5125; },
      {"animation 0 channel 0 sampler 0 input", "UNSIGNED_INT", "SCALAR FLOAT"});
  addAnimated("AnimationOutputTypeForPath", "ANIMATION_CHANNEL_TARGET_NODE_PATH_INVALID_FORMAT (translation: VEC3)",
              [=](Json& d, auto&) { animation(d)["channels"][0]["target"]["path"] = "rotation"; },
              {"animation 0 channel 0 sampler 0 output", "VEC3", "VEC4 FLOAT"});
  addAnimated("AnimationOutputCount", "ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT",
              [=](Json& d, auto&) { d["accessors"][animation(d)["samplers"][0]["output"].get<int>()]["count"] = 1; },
              {"animation 0 channel 0 sampler 0", "1 values for 2 times"});
  addAnimated("AnimationCubicSplineCount", "ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT (CUBICSPLINE: 3 a key)",
              [=](Json& d, auto&) { animation(d)["samplers"][0]["interpolation"] = "CUBICSPLINE"; },
              {"animation 0 channel 0 sampler 0", "2 values for 2 times", "needs 6"});
  addAnimated("AnimatedNodeWithMatrix", "ANIMATION_CHANNEL_TARGET_NODE_MATRIX",
              [=](Json& d, auto&) {
                d["nodes"][2].erase("translation");
                d["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 1};
              },
              {"animation 0 channel 0", "node 2 'lamp'", "matrix"});
  addAnimated("AnimationDuplicateTarget", "ANIMATION_DUPLICATE_TARGETS",
              [=](Json& d, auto&) { animation(d)["channels"].push_back(animation(d)["channels"][0]); },
              {"animation 0 channel 1", "already targets the translation", "node 2 'lamp'"});
  return cases;
}

}  // namespace

fs::path writeUnbrokenGltf(const fs::path& dir) {
  return edited("unbroken", [](Json&, auto&) {})(dir);
}

fs::path writeUnbrokenAnimatedGltf(const fs::path& dir) {
  return edited(
      "unbroken_animated", [](Json&, auto&) {}, animatedLamp)(dir);
}

const std::vector<MalformedGltf>& malformedGltfCases() {
  static const std::vector<MalformedGltf> cases = makeCases();
  return cases;
}

}  // namespace lgh::test
