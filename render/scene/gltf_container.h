#pragma once
// The glTF file as a container, before any of its content is used: reading the bytes, the GLB
// header, parsing with tinygltf, and the file-level rules tinygltf does not enforce (asset version,
// required extensions, a node with both a matrix and TRS). Internal to the loader (gltf_loader.cpp);
// problems are thrown as gltf::FileProblem (gltf_checks.h).
#include <tiny_gltf.h>

#include <filesystem>
#include <string>
#include <vector>

namespace lgh::gltf {

// The whole file. Fails on a missing, unreadable or empty file, a directory, or one of 4 GiB or
// more (tinygltf takes the size as unsigned int).
std::vector<unsigned char> readFile(const std::filesystem::path& path);

// Parses the file read from `path` (its folder resolves buffer and image URIs). A .glb's container
// is checked first, because tinygltf's own checks let a BIN chunk overrun the file. Embedded
// images stay encoded (Image::as_is), so that only the images a material uses are ever decoded.
// tinygltf's warnings are appended to `warnings`.
tinygltf::Model parseFile(const std::filesystem::path& path, const std::vector<unsigned char>& bytes,
                          std::vector<std::string>& warnings);

// glTF 1.0 files (and any other major version) differ in structure: refuse them by name instead of
// rendering whatever parts happen to parse (validator: UNKNOWN_ASSET_MAJOR_VERSION).
void checkAssetVersion(const tinygltf::Model& model);

bool extensionUsed(const tinygltf::Model& model, const char* name);

// Fails on an extension in extensionsRequired that this loader does not implement.
void checkRequiredExtensions(const tinygltf::Model& model);

// A relative URI as a file name ("a%20b.png" -> "a b.png").
std::string percentDecode(const std::string& uri);

}  // namespace lgh::gltf
