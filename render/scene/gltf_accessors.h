#pragma once
// glTF accessors decoded byte by byte: component types, glTF's normalisation of integers, byte
// strides, sparse substitution, index lists and their triangulation. Internal to the loader
// (gltf_loader.cpp), and declared here rather than hidden in it so that tests can run the decoding
// on hand-made buffers without a GL context (tests/scene/gltf_accessors_test.cpp).
//
// tinygltf 2.7 range-checks neither the indices a file contains nor the bytes an accessor reads;
// every read here is checked, and a problem is thrown as gltf::FileProblem (gltf_checks.h) naming
// `what` (the attribute or index list being read, e.g. "mesh 0 primitive 1 POSITION").
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lgh::gltf {

// Bytes per component (1, 2 or 4); 0 for INT and DOUBLE, which glTF 2.0 does not allow.
size_t componentSize(int componentType);
// Components per element of SCALAR..VEC4; 0 for matrices (no attribute this renderer reads uses them).
int componentCount(int type);
// For messages: "UNSIGNED_BYTE", "VEC3"...
const char* componentTypeName(int componentType);
const char* typeName(int type);

// One component at `p` as float. A normalized integer maps to [0, 1] (unsigned) or [-1, 1]
// (signed, where the lowest value clamps to -1, e.g. SHORT -32768 -> -1.0), by glTF 2.0's equations.
float readComponent(const unsigned char* p, int componentType, bool normalized);

bool isIndexType(int componentType);  // UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT
// One index at `p`; componentType must be one of isIndexType's.
std::uint32_t readIndex(const unsigned char* p, int componentType);

// Vertex triangles of a primitive as 3 entries each, from its index list (or 0..n-1), following
// the glTF rules for strips ({v_i, v_i+1+i%2, v_i+2-i%2}) and fans ({v_i+1, v_i+2, v_0}). Trailing
// indices of a TRIANGLES list are dropped; modes other than the three triangle modes give none.
std::vector<std::uint32_t> triangulate(int mode, const std::vector<std::uint32_t>& idx);

// model.accessors[index], or a failure saying that `what` refers to an accessor the file lacks.
const tinygltf::Accessor& accessor(const tinygltf::Model& model, int index, const std::string& what);

// The bytes of bufferView `index`, checked to lie inside its buffer; its length and byteStride
// (0: tightly packed) through the pointers.
const unsigned char* bufferViewData(const tinygltf::Model& model, int index, const std::string& what,
                                    size_t* byteLength, size_t* byteStride = nullptr);

// Every element of accessor `index` as N floats (any legal component type, normalisation applied),
// with its sparse substitutions. Instantiated for N = 1, 2, 3, 4 (in gltf_accessors.cpp).
template <int N>
std::vector<glm::vec<N, float>> readAccessor(const tinygltf::Model& model, int index, const std::string& what);

// An index list (SCALAR unsigned byte/short/int, tightly packed), as uint32.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& what);

// Vertex attribute `name` of primitive `what`, read after checking its accessor format against the
// specification (widened by KHR_mesh_quantization when `quantization`), then checked to have
// `expectedCount` elements (POSITION's; size_t(-1): any) and no NaN or Inf. Instantiated for N = 2, 3, 4.
template <int N>
std::vector<glm::vec<N, float>> readAttribute(const tinygltf::Model& model, int accessorIndex, const std::string& name,
                                              const std::string& what, size_t expectedCount, bool quantization);

// COLOR_0 as RGBA (VEC3 gets alpha 1), checked as readAttribute checks.
std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessorIndex, const std::string& what,
                                  size_t expectedCount, bool quantization);

}  // namespace lgh::gltf
