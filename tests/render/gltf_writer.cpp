#include "gltf_writer.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>

namespace lgh::test {

namespace fs = std::filesystem;
using Json = nlohmann::json;

TempDir::TempDir() {
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path candidate =
        fs::temp_directory_path() / ("lgh_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(random()));
    if (fs::create_directory(candidate)) {
      path_ = candidate;
      return;
    }
  }
  throw std::runtime_error("cannot create a temporary directory");
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

namespace {

void alignTo4(std::vector<std::uint8_t>& bytes, std::uint8_t pad = 0) {
  while (bytes.size() % 4) bytes.push_back(pad);
}

template <typename T>
void append(std::vector<std::uint8_t>& out, const T& value) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}

void appendBE32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

std::uint32_t crc32(const std::uint8_t* data, size_t size) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void pngChunk(std::vector<std::uint8_t>& png, const char* type, const std::vector<std::uint8_t>& data) {
  appendBE32(png, std::uint32_t(data.size()));
  const size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  appendBE32(png, crc32(png.data() + start, png.size() - start));
}

// min/max of a VEC3 accessor (glTF requires them for POSITION); left out if a value is not finite.
void addBounds(Json& accessor, const std::vector<glm::vec3>& v) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : v) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  accessor["min"] = {lo.x, lo.y, lo.z};
  accessor["max"] = {hi.x, hi.y, hi.z};
}

}  // namespace

int GltfWriter::addBufferView(const void* data, size_t size, size_t byteStride) {
  alignTo4(bin_);
  Json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
  if (byteStride) view["byteStride"] = byteStride;
  const auto* p = static_cast<const std::uint8_t*>(data);
  bin_.insert(bin_.end(), p, p + size);
  bufferViews_.push_back(view);
  return int(bufferViews_.size() - 1);
}

int GltfWriter::addAccessor(int bufferView, int componentType, size_t count, const std::string& type, bool normalized,
                            size_t byteOffset) {
  Json accessor = {{"componentType", componentType}, {"count", count}, {"type", type}};
  if (bufferView >= 0) accessor["bufferView"] = bufferView;
  if (byteOffset) accessor["byteOffset"] = byteOffset;
  if (normalized) accessor["normalized"] = true;
  accessors_.push_back(accessor);
  return int(accessors_.size() - 1);
}

int GltfWriter::addMesh(const std::vector<PrimitiveDesc>& primitives, const std::string& name) {
  Json mesh = {{"primitives", Json::array()}};
  if (!name.empty()) mesh["name"] = name;
  for (const PrimitiveDesc& p : primitives) {
    Json attributes = Json::object();
    const size_t n = p.positions.size();
    if (p.interleaved && !p.normals.empty()) {
      std::vector<float> data;
      for (size_t i = 0; i < n; ++i)
        for (const glm::vec3* v : {&p.positions[i], &p.normals[i]}) data.insert(data.end(), {v->x, v->y, v->z});
      const int view = addBufferView(data.data(), data.size() * 4, 24);
      attributes["POSITION"] = addAccessor(view, gltf::kFloat, n, "VEC3");
      attributes["NORMAL"] = addAccessor(view, gltf::kFloat, n, "VEC3", false, 12);
    } else if (p.positionType == gltf::kShort) {
      // 6 bytes per element, padded to 8: vertex strides must be multiples of 4.
      std::vector<std::uint8_t> data;
      std::vector<glm::vec3> stored;
      for (const glm::vec3& v : p.positions) {
        const glm::vec3 q = glm::round(p.positionNormalized ? v * 32767.0f : v);
        for (int c = 0; c < 3; ++c) append(data, std::int16_t(q[c]));
        append(data, std::int16_t(0));
        stored.push_back(q);
      }
      attributes["POSITION"] =
          addAccessor(addBufferView(data.data(), data.size(), 8), gltf::kShort, n, "VEC3", p.positionNormalized);
      addBounds(accessors_[attributes["POSITION"].get<int>()], stored);
    } else {
      attributes["POSITION"] = addAccessor(addBufferView(p.positions.data(), n * 12), gltf::kFloat, n, "VEC3");
    }
    if (!p.interleaved && !p.normals.empty()) {
      if (p.normalType == gltf::kByte) {
        std::vector<std::uint8_t> data;
        for (const glm::vec3& v : p.normals) {
          for (int c = 0; c < 3; ++c) data.push_back(std::uint8_t(std::int8_t(std::lround(v[c] * 127.0f))));
          data.push_back(0);
        }
        attributes["NORMAL"] =
            addAccessor(addBufferView(data.data(), data.size(), 4), gltf::kByte, p.normals.size(), "VEC3", true);
      } else {
        attributes["NORMAL"] =
            addAccessor(addBufferView(p.normals.data(), p.normals.size() * 12), gltf::kFloat, p.normals.size(), "VEC3");
      }
    }
    if (p.positionType == gltf::kFloat) addBounds(accessors_[attributes["POSITION"].get<int>()], p.positions);
    if (p.positionType != gltf::kFloat || p.normalType != gltf::kFloat) useExtension("KHR_mesh_quantization");
    if (!p.texcoords1.empty())
      attributes["TEXCOORD_1"] = addAccessor(addBufferView(p.texcoords1.data(), p.texcoords1.size() * 8), gltf::kFloat,
                                             p.texcoords1.size(), "VEC2");
    if (!p.colors.empty())
      attributes["COLOR_0"] =
          addAccessor(addBufferView(p.colors.data(), p.colors.size() * 16), gltf::kFloat, p.colors.size(), "VEC4");
    if (!p.texcoords.empty()) {
      const size_t m = p.texcoords.size();
      std::vector<std::uint8_t> data;
      if (p.texcoordType == gltf::kFloat) {
        data.resize(m * 8);
        std::memcpy(data.data(), p.texcoords.data(), data.size());
        attributes["TEXCOORD_0"] = addAccessor(addBufferView(data.data(), data.size()), gltf::kFloat, m, "VEC2");
      } else if (p.texcoordType == gltf::kUnsignedShort) {
        for (const glm::vec2& t : p.texcoords)
          for (float c : {t.x, t.y}) append(data, std::uint16_t(std::lround(c * 65535.0f)));
        attributes["TEXCOORD_0"] =
            addAccessor(addBufferView(data.data(), data.size()), gltf::kUnsignedShort, m, "VEC2", true);
      } else {  // unsigned byte: 2 bytes per element, but vertex strides must be multiples of 4
        for (const glm::vec2& t : p.texcoords)
          data.insert(data.end(),
                      {std::uint8_t(std::lround(t.x * 255.0f)), std::uint8_t(std::lround(t.y * 255.0f)), 0, 0});
        attributes["TEXCOORD_0"] =
            addAccessor(addBufferView(data.data(), data.size(), 4), gltf::kUnsignedByte, m, "VEC2", true);
      }
    }
    Json primitive = {{"attributes", attributes}, {"mode", p.mode}};
    if (!p.indices.empty()) {
      std::vector<std::uint8_t> data;
      for (std::uint32_t i : p.indices) {
        if (p.indexType == gltf::kUnsignedByte)
          data.push_back(std::uint8_t(i));
        else if (p.indexType == gltf::kUnsignedShort)
          append(data, std::uint16_t(i));
        else
          append(data, i);
      }
      primitive["indices"] =
          addAccessor(addBufferView(data.data(), data.size()), p.indexType, p.indices.size(), "SCALAR");
    }
    if (p.material >= 0) primitive["material"] = p.material;
    mesh["primitives"].push_back(primitive);
  }
  meshes_.push_back(mesh);
  return int(meshes_.size() - 1);
}

int GltfWriter::addMaterial(const MaterialDesc& m) {
  Json material = {{"pbrMetallicRoughness",
                    {{"baseColorFactor", {m.baseColor.r, m.baseColor.g, m.baseColor.b, m.baseColor.a}},
                     {"metallicFactor", 0.0},
                     {"roughnessFactor", 1.0}}}};
  if (!m.name.empty()) material["name"] = m.name;
  if (m.baseColorTexture >= 0) {
    material["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", m.baseColorTexture}};
    if (m.baseColorTexCoord != 0)
      material["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = m.baseColorTexCoord;
    if (!m.baseColorTransform.is_null()) {
      material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] =
          m.baseColorTransform;
      useExtension("KHR_texture_transform");
    }
  }
  if (!m.alphaMode.empty()) material["alphaMode"] = m.alphaMode;
  if (m.alphaCutoff >= 0.0) material["alphaCutoff"] = m.alphaCutoff;
  if (m.doubleSided) material["doubleSided"] = true;
  if (m.emissive != glm::vec3(0.0f)) material["emissiveFactor"] = {m.emissive.r, m.emissive.g, m.emissive.b};
  if (m.emissiveTexture >= 0) material["emissiveTexture"] = {{"index", m.emissiveTexture}};
  if (m.emissiveStrength >= 0.0f)
    material["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", m.emissiveStrength}};
  materials_.push_back(material);
  return int(materials_.size() - 1);
}

int GltfWriter::addImageUri(const std::string& uri) {
  images_.push_back({{"uri", uri}});
  return int(images_.size() - 1);
}

int GltfWriter::addImageEmbedded(const std::vector<std::uint8_t>& encoded, const std::string& mimeType) {
  images_.push_back({{"bufferView", addBufferView(encoded.data(), encoded.size())}, {"mimeType", mimeType}});
  return int(images_.size() - 1);
}

int GltfWriter::addTexture(int image) {
  textures_.push_back({{"source", image}});
  return int(textures_.size() - 1);
}

int GltfWriter::addLight(const LightDesc& l) {
  Json light = {{"type", l.type}};
  if (!l.name.empty()) light["name"] = l.name;
  if (!l.color.empty()) light["color"] = l.color;
  if (l.intensity >= 0.0) light["intensity"] = l.intensity;
  if (l.range >= 0.0) light["range"] = l.range;
  if (l.type == "spot") {
    light["spot"] = Json::object();
    if (l.innerConeAngle >= 0.0) light["spot"]["innerConeAngle"] = l.innerConeAngle;
    if (l.outerConeAngle >= 0.0) light["spot"]["outerConeAngle"] = l.outerConeAngle;
  }
  lights_.push_back(light);
  return int(lights_.size() - 1);
}

int GltfWriter::addCamera(const CameraDesc& c) {
  Json camera = {{"type", c.type}};
  if (!c.name.empty()) camera["name"] = c.name;
  if (c.type == "orthographic") {
    camera["orthographic"] = {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", c.znear}, {"zfar", c.zfar}};
  } else {
    camera["perspective"] = {{"yfov", c.yfov}, {"znear", c.znear}};
    if (c.zfar > 0.0) camera["perspective"]["zfar"] = c.zfar;  // absent: an infinite projection
    if (c.aspectRatio > 0.0) camera["perspective"]["aspectRatio"] = c.aspectRatio;
  }
  cameras_.push_back(camera);
  return int(cameras_.size() - 1);
}

int GltfWriter::addAnimationChannel(int node, const std::string& path, const std::vector<float>& times,
                                    const std::vector<float>& values, const std::string& interpolation) {
  if (animations_.empty()) animations_.push_back({{"channels", Json::array()}, {"samplers", Json::array()}});
  Json& animation = animations_[0];
  const int components = path == "rotation" ? 4 : 3;
  const int input = addAccessor(addBufferView(times.data(), times.size() * 4), gltf::kFloat, times.size(), "SCALAR");
  if (!times.empty()) {  // glTF requires the input's min and max
    accessors_[size_t(input)]["min"] = {*std::min_element(times.begin(), times.end())};
    accessors_[size_t(input)]["max"] = {*std::max_element(times.begin(), times.end())};
  }
  const int output = addAccessor(addBufferView(values.data(), values.size() * 4), gltf::kFloat,
                                 values.size() / size_t(components), components == 4 ? "VEC4" : "VEC3");
  const int sampler = int(animation["samplers"].size());
  animation["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
  animation["channels"].push_back({{"sampler", sampler}, {"target", {{"node", node}, {"path", path}}}});
  return int(animation["channels"].size() - 1);
}

int GltfWriter::addNode(const NodeDesc& n) {
  Json node = Json::object();
  if (!n.name.empty()) node["name"] = n.name;
  if (n.mesh >= 0) node["mesh"] = n.mesh;
  if (n.camera >= 0) node["camera"] = n.camera;
  if (n.light >= 0) node["extensions"]["KHR_lights_punctual"] = {{"light", n.light}};
  if (!n.children.empty()) node["children"] = n.children;
  if (!n.matrix.empty()) {
    node["matrix"] = n.matrix;
  } else {
    if (n.translation != glm::dvec3(0.0)) node["translation"] = {n.translation.x, n.translation.y, n.translation.z};
    if (n.rotation != glm::quat(1.0f, 0.0f, 0.0f, 0.0f))
      node["rotation"] = {n.rotation.x, n.rotation.y, n.rotation.z, n.rotation.w};
    if (n.scale != glm::vec3(1.0f)) node["scale"] = {n.scale.x, n.scale.y, n.scale.z};
  }
  nodes_.push_back(node);
  children_.push_back(n.children);
  return int(nodes_.size() - 1);
}

Json GltfWriter::json(const std::string& bufferUri) const {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}, {"generator", "lgh gltf_writer (tests)"}}}};
  std::vector<int> roots = roots_;
  if (!explicitRoots_) {
    std::vector<char> isChild(nodes_.size(), 0);
    for (const auto& children : children_)
      for (int c : children)
        if (c >= 0 && size_t(c) < isChild.size()) isChild[c] = 1;
    for (size_t i = 0; i < nodes_.size(); ++i)
      if (!isChild[i]) roots.push_back(int(i));
  }
  doc["scene"] = 0;
  doc["scenes"] = {{{"nodes", roots}}};
  doc["nodes"] = nodes_;
  auto put = [&](const char* key, const nlohmann::json& array) {
    if (!array.empty()) doc[key] = array;
  };
  put("meshes", meshes_);
  put("animations", animations_);
  put("accessors", accessors_);
  put("bufferViews", bufferViews_);
  put("materials", materials_);
  put("images", images_);
  put("textures", textures_);
  put("cameras", cameras_);
  if (!bin_.empty()) {
    nlohmann::json buffer = {{"byteLength", bin_.size()}};
    if (!bufferUri.empty()) buffer["uri"] = bufferUri;
    doc["buffers"] = {buffer};
  }
  std::vector<std::string> used;
  if (!lights_.empty()) {
    doc["extensions"]["KHR_lights_punctual"] = {{"lights", lights_}};
    used.push_back("KHR_lights_punctual");
  }
  for (const auto& m : materials_)
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_emissive_strength")) {
      used.push_back("KHR_materials_emissive_strength");
      break;
    }
  for (const std::vector<std::string>* list : {&extensionsUsed_, &extensionsRequired_})
    for (const std::string& e : *list)
      if (std::find(used.begin(), used.end(), e) == used.end()) used.push_back(e);
  if (!used.empty()) doc["extensionsUsed"] = used;
  if (!extensionsRequired_.empty()) doc["extensionsRequired"] = extensionsRequired_;
  return doc;
}

fs::path GltfWriter::write(const fs::path& file, Format format) const {
  switch (format) {
    case Format::Gltf: {
      const std::string binName = file.stem().string() + ".bin";
      writeGltfFiles(file, json(bin_.empty() ? "" : binName), bin_, bin_.empty() ? "" : binName);
      break;
    }
    case Format::GltfEmbedded:
      writeGltfFiles(file, json("data:application/octet-stream;base64," + base64(bin_)), {}, "");
      break;
    case Format::Glb:
      writeGlbFile(file, json(""), bin_);
      break;
  }
  return file;
}

void writeTextFile(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

void writeGltfFiles(const fs::path& gltf, const Json& doc, const std::vector<std::uint8_t>& bin,
                    const std::string& binName) {
  writeTextFile(gltf, doc.dump(1));
  if (!binName.empty()) {
    std::ofstream out(gltf.parent_path() / binName, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    if (!out) throw std::runtime_error("cannot write " + binName);
  }
}

void writeGlbFile(const fs::path& glb, const Json& doc, const std::vector<std::uint8_t>& bin) {
  const std::string text = doc.dump();
  std::vector<std::uint8_t> jsonChunk(text.begin(), text.end()), binChunk(bin);
  alignTo4(jsonChunk, ' ');
  alignTo4(binChunk, 0);
  std::vector<std::uint8_t> out;
  const std::uint32_t total =
      12 + 8 + std::uint32_t(jsonChunk.size()) + (bin.empty() ? 0 : 8 + std::uint32_t(binChunk.size()));
  out.insert(out.end(), {'g', 'l', 'T', 'F'});
  append(out, std::uint32_t(2));
  append(out, total);
  append(out, std::uint32_t(jsonChunk.size()));
  out.insert(out.end(), {'J', 'S', 'O', 'N'});
  out.insert(out.end(), jsonChunk.begin(), jsonChunk.end());
  if (!bin.empty()) {
    append(out, std::uint32_t(binChunk.size()));
    out.insert(out.end(), {'B', 'I', 'N', 0});
    out.insert(out.end(), binChunk.begin(), binChunk.end());
  }
  std::ofstream file(glb, std::ios::binary);
  file.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
  if (!file) throw std::runtime_error("cannot write " + glb.string());
}

PrimitiveDesc quad(const glm::vec3& corner, const glm::vec3& u, const glm::vec3& v, int material) {
  PrimitiveDesc p;
  p.positions = {corner, corner + u, corner + u + v, corner + v};
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  p.normals = {n, n, n, n};
  p.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  return p;
}

PrimitiveDesc box(const glm::vec3& center, const glm::vec3& h, int material) {
  PrimitiveDesc out;
  out.material = material;
  for (int axis = 0; axis < 3; ++axis) {
    // (u, v) with cross(u, v) = +axis; swapped for the -axis face so every face points outward.
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 u(0.0f), v(0.0f), offset(0.0f);
      u[a] = 2.0f * h[a];
      v[b] = 2.0f * h[b];
      if (sign < 0) std::swap(u, v);
      offset[axis] = sign * h[axis];
      offset[a] = -h[a];
      offset[b] = -h[b];
      const PrimitiveDesc face = quad(center + offset, u, v, material);
      const auto base = std::uint32_t(out.positions.size());
      out.positions.insert(out.positions.end(), face.positions.begin(), face.positions.end());
      out.normals.insert(out.normals.end(), face.normals.begin(), face.normals.end());
      out.texcoords.insert(out.texcoords.end(), face.texcoords.begin(), face.texcoords.end());
      for (std::uint32_t i : face.indices) out.indices.push_back(base + i);
    }
  }
  return out;
}

std::vector<std::uint8_t> encodePng(int width, int height, const std::vector<std::uint8_t>& rgba) {
  // Raw scanlines (filter byte 0 + RGBA), wrapped in zlib "stored" blocks: no compressor needed.
  std::vector<std::uint8_t> raw;
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    const auto* row = rgba.data() + size_t(y) * size_t(width) * 4;
    raw.insert(raw.end(), row, row + size_t(width) * 4);
  }
  std::vector<std::uint8_t> z = {0x78, 0x01};
  for (size_t pos = 0; pos < raw.size() || pos == 0;) {
    const size_t n = std::min<size_t>(65535, raw.size() - pos);
    const bool last = pos + n >= raw.size();
    z.push_back(last ? 1 : 0);
    z.push_back(std::uint8_t(n & 0xFF));
    z.push_back(std::uint8_t(n >> 8));
    z.push_back(std::uint8_t(~n & 0xFF));
    z.push_back(std::uint8_t((~n >> 8) & 0xFF));
    z.insert(z.end(), raw.begin() + std::ptrdiff_t(pos), raw.begin() + std::ptrdiff_t(pos + n));
    pos += n;
    if (last) break;
  }
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  appendBE32(z, (b << 16) | a);

  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> header;
  appendBE32(header, std::uint32_t(width));
  appendBE32(header, std::uint32_t(height));
  header.insert(header.end(), {8, 6, 0, 0, 0});  // 8-bit RGBA, deflate, no filter, no interlace
  pngChunk(png, "IHDR", header);
  pngChunk(png, "IDAT", z);
  pngChunk(png, "IEND", {});
  return png;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t(bytes[i]) << 16) | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

}  // namespace lgh::test
