// The one translation unit that compiles tinygltf (header-only mode).
//
// Why not Debian's libtinygltf.so: it decodes every image while parsing (even images no material
// uses) and fails the whole load when one image cannot be decoded. Built here with
// TINYGLTF_NO_EXTERNAL_IMAGE / TINYGLTF_NO_STB_IMAGE / TINYGLTF_NO_STB_IMAGE_WRITE (set on the
// lgh_engine target in render/CMakeLists.txt), tinygltf only parses the JSON and loads buffers;
// external images keep their URI, and embedded ones are handed to the loader's callback, which
// keeps the encoded bytes. gltf_materials.cpp decodes what the materials reference.
#define TINYGLTF_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <tiny_gltf.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
