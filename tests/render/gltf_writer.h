#pragma once
// A small glTF 2.0 writer for loader tests: builds meshes (quads, boxes, any triangles), node
// hierarchies, materials, textures, KHR_lights_punctual lights and cameras in memory, and writes
// them as .gltf + .bin, .gltf with an embedded (data URI) buffer, or .glb. Tests that need a
// broken file take json() / binary(), damage them, and write them with writeGltfFiles/writeGlbFile.
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lgh::test {

// A fresh folder under the system temp directory, removed with everything in it on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// glTF numeric constants, spelled out for readability in tests.
namespace gltf {
constexpr int kPoints = 0, kLines = 1, kTriangles = 4, kTriangleStrip = 5, kTriangleFan = 6;
constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
}  // namespace gltf

// Descriptions with chainable setters, e.g. NodeDesc{}.named("lamp").withLight(0).translated({0, 2, 0}).
struct PrimitiveDesc {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // empty: no NORMAL attribute
  std::vector<glm::vec2> texcoords;    // empty: no TEXCOORD_0
  std::vector<std::uint32_t> indices;  // empty: non-indexed
  int mode = gltf::kTriangles;
  int material = -1;                   // -1: none (glTF default material)
  int indexType = gltf::kUnsignedInt;  // kUnsignedByte / kUnsignedShort / kUnsignedInt
  int texcoordType = gltf::kFloat;     // kFloat, or normalized kUnsignedByte / kUnsignedShort
  bool interleaved = false;            // POSITION + NORMAL in one bufferView with byteStride 24
  std::vector<glm::vec2> texcoords1;   // empty: no TEXCOORD_1 (float)
  std::vector<glm::vec4> colors;       // empty: no COLOR_0 (float VEC4)
  // KHR_mesh_quantization: POSITION as kShort (normalized: p * 32767; else rounded integers) and
  // NORMAL as normalized kByte; the writer declares the extension when a primitive uses it.
  int positionType = gltf::kFloat;
  bool positionNormalized = false;
  int normalType = gltf::kFloat;
};

struct MaterialDesc {
  std::string name;
  glm::vec4 baseColor{1.0f};
  glm::vec3 emissive{0.0f};
  float emissiveStrength = -1.0f;  // < 0: no KHR_materials_emissive_strength
  int baseColorTexture = -1;       // texture index
  int emissiveTexture = -1;
  int baseColorTexCoord = 0;
  std::string alphaMode;      // empty: omitted (OPAQUE)
  double alphaCutoff = -1.0;  // < 0: omitted (0.5)
  bool doubleSided = false;
  nlohmann::json baseColorTransform;  // KHR_texture_transform object on the base colour texture; null: none

  MaterialDesc& named(std::string n) {
    name = std::move(n);
    return *this;
  }
  MaterialDesc& withBaseColor(const glm::vec4& c) {
    baseColor = c;
    return *this;
  }
  MaterialDesc& withEmission(const glm::vec3& e, float strength = -1.0f) {
    emissive = e;
    emissiveStrength = strength;
    return *this;
  }
  MaterialDesc& withBaseColorTexture(int texture, int texCoord = 0) {
    baseColorTexture = texture;
    baseColorTexCoord = texCoord;
    return *this;
  }
  MaterialDesc& withAlphaMask(double cutoff) {
    alphaMode = "MASK";
    alphaCutoff = cutoff;
    return *this;
  }
  MaterialDesc& twoSided() {
    doubleSided = true;
    return *this;
  }
  MaterialDesc& withBaseColorTransform(nlohmann::json transform) {
    baseColorTransform = std::move(transform);
    return *this;
  }
  MaterialDesc& withEmissiveTexture(int texture) {
    emissiveTexture = texture;
    return *this;
  }
};

struct LightDesc {  // fields at their "omit" value are left out, so the glTF defaults apply
  std::string name;
  std::string type = "point";
  std::vector<double> color;                            // empty: omitted (white)
  double intensity = -1.0;                              // < 0: omitted (1)
  double range = -1.0;                                  // < 0: omitted (infinite)
  double innerConeAngle = -1.0, outerConeAngle = -1.0;  // < 0: omitted (0, pi/4)

  LightDesc& named(std::string n) {
    name = std::move(n);
    return *this;
  }
  LightDesc& ofType(std::string t) {
    type = std::move(t);
    return *this;
  }
  LightDesc& withColor(std::vector<double> c) {
    color = std::move(c);
    return *this;
  }
  LightDesc& withIntensity(double i) {
    intensity = i;
    return *this;
  }
  LightDesc& withRange(double r) {
    range = r;
    return *this;
  }
  LightDesc& withCone(double inner, double outer) {
    innerConeAngle = inner;
    outerConeAngle = outer;
    return *this;
  }
};

struct CameraDesc {
  std::string name;  // empty: omitted
  std::string type = "perspective";
  double yfov = 0.8, aspectRatio = 0.0 /* 0: omitted */, znear = 0.01, zfar = 100.0 /* perspective, 0: omitted */;

  CameraDesc& named(std::string n) {
    name = std::move(n);
    return *this;
  }
  CameraDesc& ofType(std::string t) {
    type = std::move(t);
    return *this;
  }
  CameraDesc& withYfov(double radians) {
    yfov = radians;
    return *this;
  }
  CameraDesc& withAspectRatio(double a) {
    aspectRatio = a;
    return *this;
  }
  CameraDesc& withClip(double nearPlane, double farPlane) {
    znear = nearPlane;
    zfar = farPlane;
    return *this;
  }
};

struct NodeDesc {
  std::string name;
  int mesh = -1, camera = -1, light = -1;
  std::vector<int> children;
  glm::dvec3 translation{0.0};                 // double: tests place scenes far from the origin
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // (w, x, y, z)
  glm::vec3 scale{1.0f};
  std::vector<double> matrix;  // 16 numbers, column-major: written instead of TRS when set

  NodeDesc& named(std::string n) {
    name = std::move(n);
    return *this;
  }
  NodeDesc& withMesh(int m) {
    mesh = m;
    return *this;
  }
  NodeDesc& withCamera(int c) {
    camera = c;
    return *this;
  }
  NodeDesc& withLight(int l) {
    light = l;
    return *this;
  }
  NodeDesc& withChildren(std::vector<int> c) {
    children = std::move(c);
    return *this;
  }
  NodeDesc& translated(const glm::dvec3& t) {
    translation = t;
    return *this;
  }
  NodeDesc& rotated(const glm::quat& r) {
    rotation = r;
    return *this;
  }
  NodeDesc& scaled(const glm::vec3& s) {
    scale = s;
    return *this;
  }
  NodeDesc& withMatrix(std::vector<double> m) {
    matrix = std::move(m);
    return *this;
  }
};

class GltfWriter {
 public:
  enum class Format { Gltf, GltfEmbedded, Glb };  // .gltf + .bin, .gltf with data URI, .glb

  int addMesh(const std::vector<PrimitiveDesc>& primitives, const std::string& name = "");
  int addMaterial(const MaterialDesc& material);
  int addImageUri(const std::string& uri);  // an external file (or a data URI) beside the .gltf
  int addImageEmbedded(const std::vector<std::uint8_t>& encoded, const std::string& mimeType = "image/png");
  int addTexture(int image);
  int addLight(const LightDesc& light);
  int addCamera(const CameraDesc& camera);
  int addNode(const NodeDesc& node);
  // Scene 0's root nodes; by default every node that is nobody's child.
  void setSceneRoots(std::vector<int> roots) {
    roots_ = std::move(roots);
    explicitRoots_ = true;
  }
  void requireExtension(const std::string& name) { extensionsRequired_.push_back(name); }
  void useExtension(const std::string& name) { extensionsUsed_.push_back(name); }

  // A channel of animation 0 (made by the first call) moving `path` ("translation", "rotation", "scale")
  // of `node` through `values` (3 floats a key, rotation 4: x, y, z, w; CUBICSPLINE 3 entries a key:
  // in-tangent, value, out-tangent) at `times`, with a sampler of its own. Returns the channel's index.
  int addAnimationChannel(int node, const std::string& path, const std::vector<float>& times,
                          const std::vector<float>& values, const std::string& interpolation = "LINEAR");

  // Low-level pieces for hand-made accessors (sparse, odd strides...).
  int addBufferView(const void* data, size_t size, size_t byteStride = 0);
  int addAccessor(int bufferView, int componentType, size_t count, const std::string& type, bool normalized = false,
                  size_t byteOffset = 0);

  // The document; buffer 0 gets `bufferUri` ("" = the GLB BIN chunk).
  nlohmann::json json(const std::string& bufferUri) const;
  const std::vector<std::uint8_t>& binary() const { return bin_; }

  // Writes `file` (and `<stem>.bin` beside it for Format::Gltf); returns `file`.
  std::filesystem::path write(const std::filesystem::path& file, Format format = Format::Gltf) const;

 private:
  nlohmann::json accessors_ = nlohmann::json::array(), bufferViews_ = nlohmann::json::array(),
                 meshes_ = nlohmann::json::array(), materials_ = nlohmann::json::array(),
                 images_ = nlohmann::json::array(), textures_ = nlohmann::json::array(),
                 lights_ = nlohmann::json::array(), cameras_ = nlohmann::json::array(),
                 nodes_ = nlohmann::json::array(), animations_ = nlohmann::json::array();
  std::vector<std::uint8_t> bin_;
  std::vector<int> roots_;
  bool explicitRoots_ = false;
  std::vector<std::string> extensionsRequired_, extensionsUsed_;
  std::vector<std::vector<int>> children_;
};

// Writes a .gltf whose buffer 0 is `binName` beside it (and that .bin, unless binName is empty).
void writeGltfFiles(const std::filesystem::path& gltf, const nlohmann::json& doc, const std::vector<std::uint8_t>& bin,
                    const std::string& binName);
void writeGlbFile(const std::filesystem::path& glb, const nlohmann::json& doc, const std::vector<std::uint8_t>& bin);
void writeTextFile(const std::filesystem::path& file, const std::string& text);

// Geometry: a quad corner, corner+u, corner+u+v, corner+v as two counter-clockwise triangles
// (front face and normal along cross(u, v)); a box with outward faces.
PrimitiveDesc quad(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int material = -1);
PrimitiveDesc box(const glm::vec3& center, const glm::vec3& halfExtent, int material = -1);

// An uncompressed-deflate RGBA8 PNG (rows top-down), decodable by any PNG reader.
std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgba);
std::string base64(const std::vector<std::uint8_t>& bytes);

}  // namespace lgh::test
