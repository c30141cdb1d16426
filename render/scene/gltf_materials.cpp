#include "render/scene/gltf_materials.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "render/scene/gltf_accessors.h"
#include "render/scene/gltf_container.h"

// stb_image with internal linkage: only this file decodes images, and STB_IMAGE_STATIC keeps its
// symbols from clashing with any other copy of stb in the program.
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO  // images come from memory (files are read by the loader)
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace lgh::gltf {
namespace {

namespace fs = std::filesystem;

// KHR_texture_transform of a texture slot as a 3x3 matrix on (u, v, 1): translation * rotation *
// scale, rotation counter-clockwise by `rotation` radians (the extension's definition).
glm::mat3 uvTransform(const tinygltf::TextureInfo& info, const std::string& what) {
  const auto ext = info.extensions.find("KHR_texture_transform");
  if (info.index < 0 || ext == info.extensions.end()) return glm::mat3(1.0f);
  const tinygltf::Value& t = ext->second;
  const auto vec2 = [&](const char* key, glm::dvec2 fallback) {
    if (!t.Has(key)) return fallback;
    const tinygltf::Value& v = t.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      fail(what + ": KHR_texture_transform." + key + " must be 2 numbers");
    return glm::dvec2(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
  };
  const glm::dvec2 offset = vec2("offset", glm::dvec2(0.0)), scale = vec2("scale", glm::dvec2(1.0));
  double rotation = 0.0;
  if (t.Has("rotation")) {
    if (!t.Get("rotation").IsNumber()) fail(what + ": KHR_texture_transform.rotation must be a number");
    rotation = t.Get("rotation").GetNumberAsDouble();
  }
  for (double v : {offset.x, offset.y, scale.x, scale.y, rotation})
    if (!fitsFloat(v)) fail(what + ": KHR_texture_transform has a non-finite number " + number(v));
  const double c = std::cos(rotation), s = std::sin(rotation);
  // Columns of translation * rotation * scale (column-major, as GLSL's mat3).
  return glm::mat3(glm::vec3(float(c * scale.x), float(s * scale.x), 0.0f),
                   glm::vec3(float(-s * scale.y), float(c * scale.y), 0.0f),
                   glm::vec3(float(offset.x), float(offset.y), 1.0f));
}

// The textures of a scene's materials: each image is decoded on its first use by a material and
// shared by every later one.
class TextureDecoder {
 public:
  TextureDecoder(const tinygltf::Model& model, const fs::path& file, Scene& scene)
      : model_(model), file_(file), scene_(scene) {}

  // Index into scene_.textures for a material's texture slot, -1 when absent or unusable (with
  // a warning: a missing texture costs detail, not the scene).
  int textureFor(const tinygltf::TextureInfo& info, const std::string& material, const char* slot) {
    if (info.index < 0) return -1;
    if (size_t(info.index) >= model_.textures.size())
      fail("material '" + material + "' " + slot + " texture refers to texture " + std::to_string(info.index) +
           ", but the file has " + std::to_string(model_.textures.size()) + " textures");
    const int texCoord = effectiveTexCoord(info);
    if (texCoord < 0) fail("material '" + material + "' " + slot + " texture has a negative texCoord");
    if (texCoord > 1) {
      scene_.warnings.push_back("material '" + material + "': " + slot + " texture uses TEXCOORD_" +
                                std::to_string(texCoord) +
                                "; only TEXCOORD_0 and TEXCOORD_1 are loaded, so the texture is ignored");
      return -1;
    }
    const int source = model_.textures[info.index].source;
    if (source < 0) {
      scene_.warnings.push_back("material '" + material + "': texture " + std::to_string(info.index) +
                                " has no image source this loader can read; using the factor only");
      return -1;
    }
    if (size_t(source) >= model_.images.size())
      fail("texture " + std::to_string(info.index) + " refers to image " + std::to_string(source) +
           ", but the file has " + std::to_string(model_.images.size()) + " images");
    if (imageTexture_.empty()) imageTexture_.assign(model_.images.size(), kNotDecoded);
    if (imageTexture_[source] == kNotDecoded) imageTexture_[source] = decodeImage(size_t(source), material);
    return imageTexture_[source];
  }

 private:
  // Decodes image `i` into scene_.textures (8-bit RGBA); -1 plus a warning if it cannot be had.
  int decodeImage(size_t i, const std::string& material) {
    const tinygltf::Image& image = model_.images[i];
    const std::string name = !image.name.empty()  ? image.name
                             : !image.uri.empty() ? image.uri
                                                  : "image " + std::to_string(i);
    std::vector<unsigned char> fileBytes;
    const unsigned char* bytes = nullptr;
    size_t size = 0;
    if (image.bufferView >= 0) {
      bytes = bufferViewData(model_, image.bufferView, "image " + std::to_string(i), &size);
    } else if (image.as_is) {  // data URI, kept encoded by parseFile's image callback
      bytes = image.image.data();
      size = image.image.size();
    } else if (!image.uri.empty()) {
      const fs::path file = file_.parent_path() / fs::u8path(percentDecode(image.uri));
      std::ifstream in(file, std::ios::binary);
      if (!in) {
        scene_.warnings.push_back("texture image '" + image.uri + "' not found (" + file.string() + "); material '" +
                                  material + "' uses its factor only");
        return -1;
      }
      fileBytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      bytes = fileBytes.data();
      size = fileBytes.size();
    }
    int width = 0, height = 0, channels = 0;
    stbi_uc* pixels = nullptr;
    if (bytes && size > 0 && size < size_t(std::numeric_limits<int>::max()))
      pixels = stbi_load_from_memory(bytes, int(size), &width, &height, &channels, 4);
    if (!pixels) {
      scene_.warnings.push_back("texture image '" + name + "' cannot be decoded (" +
                                (bytes && size ? std::string(stbi_failure_reason()) : std::string("no data")) +
                                "); material '" + material + "' uses its factor only");
      return -1;
    }
    Texture texture;
    texture.name = name;
    texture.width = width;
    texture.height = height;
    texture.rgba.assign(pixels, pixels + size_t(width) * size_t(height) * 4);
    stbi_image_free(pixels);
    scene_.textures.push_back(std::move(texture));
    return int(scene_.textures.size() - 1);
  }

  static constexpr int kNotDecoded = -2;

  const tinygltf::Model& model_;
  const fs::path& file_;
  Scene& scene_;
  std::vector<int> imageTexture_;  // image → texture index, -1 failed, kNotDecoded
};

}  // namespace

int effectiveTexCoord(const tinygltf::TextureInfo& info) {
  const auto ext = info.extensions.find("KHR_texture_transform");
  if (ext != info.extensions.end() && ext->second.IsObject() && ext->second.Has("texCoord") &&
      ext->second.Get("texCoord").IsNumber())
    return ext->second.Get("texCoord").GetNumberAsInt();
  return info.texCoord;
}

void loadMaterials(const tinygltf::Model& model, const fs::path& file,
                   const std::vector<std::vector<std::uint32_t>>& trianglesByMaterial, bool meshesUseDefaultMaterial,
                   WarningGroup& blendMaterials, Scene& scene) {
  TextureDecoder textures(model, file, scene);
  scene.materials.resize(model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& src = model.materials[i];
    Material& dst = scene.materials[i];
    dst.name = src.name.empty() ? "material " + std::to_string(i) : src.name;
    const std::string what = label("material", i, src.name);
    const auto& bc = src.pbrMetallicRoughness.baseColorFactor;
    if (bc.size() != 4) fail(what + " has a baseColorFactor that is not 4 numbers");
    for (double c : bc)
      if (!(c >= 0.0 && c <= 1.0)) fail(what + " has a baseColorFactor component " + number(c) + " outside [0, 1]");
    dst.baseColorFactor = glm::vec4(bc[0], bc[1], bc[2], bc[3]);
    glm::vec3 emissive(0.0f);
    if (src.emissiveFactor.size() == 3)
      emissive = glm::vec3(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
    else if (!src.emissiveFactor.empty())
      fail(what + " has an emissiveFactor that is not 3 numbers");
    for (double c : src.emissiveFactor)
      if (!(c >= 0.0 && c <= 1.0)) fail(what + " has an emissiveFactor component " + number(c) + " outside [0, 1]");
    if (src.alphaMode == "OPAQUE") {
      dst.alphaMode = AlphaMode::Opaque;
    } else if (src.alphaMode == "MASK") {
      dst.alphaMode = AlphaMode::Mask;
    } else if (src.alphaMode == "BLEND") {
      dst.alphaMode = AlphaMode::Blend;
      blendMaterials.add(dst.name);
    } else {
      fail(what + " has alphaMode '" + src.alphaMode + "' (expected OPAQUE, MASK or BLEND)");
    }
    if (!(src.alphaCutoff >= 0.0) || !fitsFloat(src.alphaCutoff))
      fail(what + " has alphaCutoff " + number(src.alphaCutoff) + " (must be a finite number >= 0)");
    dst.alphaCutoff = float(src.alphaCutoff);
    dst.doubleSided = src.doubleSided;
    // KHR_materials_emissive_strength scales emissiveFactor (glTF caps the factor at 1).
    const auto ext = src.extensions.find("KHR_materials_emissive_strength");
    if (ext != src.extensions.end() && ext->second.Has("emissiveStrength")) {
      const tinygltf::Value& strength = ext->second.Get("emissiveStrength");
      if (!strength.IsNumber() || !(strength.GetNumberAsDouble() >= 0.0) || !fitsFloat(strength.GetNumberAsDouble()))
        fail(what + ": KHR_materials_emissive_strength.emissiveStrength must be a number >= 0");
      emissive *= float(strength.GetNumberAsDouble());
    }
    if (!finite(emissive) || glm::any(glm::lessThan(emissive, glm::vec3(0.0f))))
      fail(what + " has a negative or non-finite emission");
    dst.emission = emissive;
    // Textures are decoded only for materials the displayed triangles use.
    if (i < trianglesByMaterial.size() && !trianglesByMaterial[i].empty()) {
      dst.baseColorTexture = textures.textureFor(src.pbrMetallicRoughness.baseColorTexture, dst.name, "base colour");
      dst.emissiveTexture = textures.textureFor(src.emissiveTexture, dst.name, "emissive");
      dst.baseColorTexCoord = effectiveTexCoord(src.pbrMetallicRoughness.baseColorTexture);
      dst.emissiveTexCoord = effectiveTexCoord(src.emissiveTexture);
      dst.baseColorUvTransform = uvTransform(src.pbrMetallicRoughness.baseColorTexture, what + " base colour texture");
      dst.emissiveUvTransform = uvTransform(src.emissiveTexture, what + " emissive texture");
    }
  }
  if (meshesUseDefaultMaterial || scene.materials.empty()) {
    // glTF's default material is white; grey keeps a scene without materials readable.
    Material grey;
    grey.name = "default";
    grey.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    scene.materials.push_back(grey);
  }
}

}  // namespace lgh::gltf
