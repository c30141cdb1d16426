#include "render/scene/gltf_container.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "render/scene/gltf_checks.h"

namespace lgh::gltf {
namespace {

namespace fs = std::filesystem;

const char* const kSupportedExtensions[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                            "KHR_texture_transform", "KHR_mesh_quantization"};

// Image callback for tinygltf: keep embedded (data URI) images encoded, so that only the images a
// material uses are ever decoded. Images in a bufferView are left alone here; the loader reads
// them from the buffer itself, with bounds checks tinygltf 2.7 does not make.
bool keepEncodedImage(tinygltf::Image* image, const int /*index*/, std::string* /*err*/, std::string* /*warn*/,
                      int /*reqWidth*/, int /*reqHeight*/, const unsigned char* bytes, int size, void* /*user*/) {
  if (image->bufferView >= 0) return true;
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;
  return true;
}

std::uint32_t readU32(const unsigned char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// tinygltf's checks of the GLB container are incomplete (the BIN chunk may overrun the file by
// its 8-byte header), so the container is validated here first, with plain messages.
void checkGlbHeader(const std::vector<unsigned char>& b) {
  if (b.size() < 12)
    fail("bad .glb header: the file has " + std::to_string(b.size()) + " bytes, less than the 12-byte header");
  if (std::memcmp(b.data(), "glTF", 4) != 0) fail("bad .glb header: the file does not start with the magic 'glTF'");
  const std::uint32_t version = readU32(&b[4]), length = readU32(&b[8]);
  if (version != 2) fail("bad .glb header: container version " + std::to_string(version) + ", expected 2");
  if (length > b.size())
    fail("bad .glb header: declares " + std::to_string(length) + " bytes but the file has " + std::to_string(b.size()) +
         " (truncated?)");
  if (length < 20)
    fail("bad .glb header: declared length " + std::to_string(length) + " leaves no room for the JSON chunk");
  const std::uint32_t jsonLength = readU32(&b[12]);
  if (std::memcmp(&b[16], "JSON", 4) != 0) fail("bad .glb header: the first chunk is not of type JSON");
  const std::uint64_t jsonEnd = 20ull + jsonLength;
  if (jsonLength == 0 || jsonEnd > length)
    fail("bad .glb header: the JSON chunk length " + std::to_string(jsonLength) + " overruns the file");
  if (jsonEnd < length) {
    if (jsonEnd + 8 > length) fail("bad .glb header: a chunk header is cut off after the JSON chunk");
    const std::uint32_t binLength = readU32(&b[jsonEnd]);
    if (std::memcmp(&b[jsonEnd + 4], "BIN\0", 4) != 0) fail("bad .glb header: the second chunk is not of type BIN");
    if (jsonEnd + 8 + binLength > length)
      fail("bad .glb header: the BIN chunk length " + std::to_string(binLength) + " overruns the file");
  }
}

// tinygltf's messages are terse; say in our words what kind of problem it is, keep its details.
std::string explainParseError(std::string err) {
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  for (char& c : err)
    if (c == '\n') c = ';';
  auto has = [&](const char* s) { return err.find(s) != std::string::npos; };
  if (has("json.exception") || has("parse error") || has("JSON string too short") || has("Root element is not"))
    return "invalid JSON: " + err;
  if (has("File size mismatch") || has("Invalid `byteLength'"))
    return "buffer data is shorter or longer than its declared byteLength (truncated .bin?): " + err;
  if (has("File not found") || has("File read error") || has("File is empty"))
    return "cannot load a file the glTF refers to: " + err;
  if (has("decode 'uri'")) return "invalid data URI: " + err;
  if (has("\"asset\" object not found"))  // tinygltf says this also when only asset.version is missing
    return "asset or asset.version is missing (a glTF 2.0 file declares \"asset\": {\"version\": \"2.0\"}): " + err;
  return "invalid glTF: " + (err.empty() ? std::string("tinygltf rejected the file") : err);
}

// tinygltf reads a node's translation/rotation/scale only when it has no matrix, so a file with both
// (NODE_MATRIX_TRS: which one the author meant is unknown) looks valid after parsing. The raw JSON
// (a .glb's JSON chunk, validated by checkGlbHeader) is read again for that.
void checkWhatTinygltfDrops(const tinygltf::Model& model, const std::vector<unsigned char>& bytes, bool binary) {
  const unsigned char* begin = bytes.data();
  size_t size = bytes.size();
  if (binary) {
    size = readU32(&bytes[12]);
    begin += 20;
  }
  const nlohmann::json doc = nlohmann::json::parse(begin, begin + size, nullptr, false);
  if (!doc.is_object() || !doc.contains("nodes") || !doc["nodes"].is_array()) return;
  const nlohmann::json& nodes = doc["nodes"];
  for (size_t i = 0; i < nodes.size() && i < model.nodes.size(); ++i)
    if (nodes[i].is_object() && nodes[i].contains("matrix") &&
        (nodes[i].contains("translation") || nodes[i].contains("rotation") || nodes[i].contains("scale")))
      fail(label("node", i, model.nodes[i].name) +
           " has both a matrix and translation/rotation/scale (glTF allows one or the other)");
}

}  // namespace

std::vector<unsigned char> readFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail("file not found");
  if (fs::is_directory(status)) fail("is a directory, not a glTF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot open file for reading: " + std::string(std::strerror(errno)));
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail("error while reading the file");
  if (bytes.empty()) fail("file is empty");
  if (bytes.size() >= std::numeric_limits<unsigned int>::max()) fail("file is larger than 4 GiB");
  return bytes;
}

tinygltf::Model parseFile(const fs::path& path, const std::vector<unsigned char>& bytes,
                          std::vector<std::string>& warnings) {
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".glb" || binary) checkGlbHeader(bytes);

  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(&keepEncodedImage, nullptr);
  std::string err, warn;
  const std::string baseDir = path.parent_path().string();
  bool ok = false;
  try {
    ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), baseDir)
                : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                           unsigned(bytes.size()), baseDir);
  } catch (const std::exception& e) {  // e.g. std::out_of_range on an empty data URI
    ok = false;
    err += e.what();
  }
  if (!ok) fail(explainParseError(err));
  checkWhatTinygltfDrops(model, bytes, binary);
  std::istringstream lines(warn);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) warnings.push_back("tinygltf: " + line);
  return model;
}

void checkAssetVersion(const tinygltf::Model& model) {
  const std::string& version = model.asset.version;
  if (version.empty()) fail("asset.version is missing (a glTF 2.0 file declares \"asset\": {\"version\": \"2.0\"})");
  const size_t dot = version.find('.');
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  const bool wellFormed = dot != std::string::npos && dot > 0 && dot + 1 < version.size() &&
                          std::all_of(version.begin(), version.begin() + std::ptrdiff_t(dot), digit) &&
                          std::all_of(version.begin() + std::ptrdiff_t(dot) + 1, version.end(), digit);
  if (!wellFormed) fail("asset.version '" + version + "' is not of the form MAJOR.MINOR");
  const std::string major = version.substr(0, dot);
  if (major != "2")
    fail("asset.version is '" + version + "': this is not a glTF 2.0 file (only major version 2 is supported" +
         (major == "1" ? "; glTF 1.0 files can be converted with a tool such as gltf-pipeline)" : ")"));
}

bool extensionUsed(const tinygltf::Model& model, const char* name) {
  return std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) != model.extensionsUsed.end() ||
         std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), name) !=
             model.extensionsRequired.end();
}

void checkRequiredExtensions(const tinygltf::Model& model) {
  for (const std::string& required : model.extensionsRequired) {
    if (std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), required) !=
        std::end(kSupportedExtensions))
      continue;
    std::string supported;
    for (const char* s : kSupportedExtensions) supported += (supported.empty() ? "" : ", ") + std::string(s);
    fail("requires the glTF extension '" + required + "', which this loader does not support (supported: " + supported +
         ")");
  }
}

std::string percentDecode(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace lgh::gltf
