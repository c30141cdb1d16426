#pragma once
// glTF materials to Scene::materials, and the images they use decoded to Scene::textures (the one
// place images are decoded: tinygltf is built without its image code, tinygltf_impl.cpp). Internal
// to the loader (gltf_loader.cpp); problems are thrown as gltf::FileProblem (gltf_checks.h).
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "render/scene/gltf_checks.h"
#include "render/scene/scene.h"

namespace lgh::gltf {

// The TEXCOORD set a texture reads: textureInfo.texCoord, overridden by KHR_texture_transform.texCoord.
int effectiveTexCoord(const tinygltf::TextureInfo& info);

// Fills scene.materials, one per material of the file at the same index, then glTF's default
// material (as grey) after them when `meshesUseDefaultMaterial` or the file has none. Images are
// decoded only for materials with triangles in `trianglesByMaterial` (a file may carry images that
// nothing displayed uses), each at most once; one that cannot be had costs detail, not the scene: a
// warning in scene.warnings, and the material keeps its factor alone. `file` is the glTF file, whose
// folder resolves image URIs. BLEND materials are counted in `blendMaterials`.
void loadMaterials(const tinygltf::Model& model, const std::filesystem::path& file,
                   const std::vector<std::vector<std::uint32_t>>& trianglesByMaterial, bool meshesUseDefaultMaterial,
                   WarningGroup& blendMaterials, Scene& scene);

}  // namespace lgh::gltf
