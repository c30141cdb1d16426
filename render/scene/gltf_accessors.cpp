#include "render/scene/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "render/scene/gltf_checks.h"

namespace lgh::gltf {
namespace {

template <int N>
bool finiteVec(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// The accessor formats glTF 2.0 allows for the vertex attributes this renderer reads (spec 3.7.2.1),
// widened by KHR_mesh_quantization when the file uses it. A format outside these lists is an error
// (validator: MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT): reading it anyway would guess.
struct AttributeFormat {
  int type, componentType;
  bool normalized;
};
bool allowedFormat(const std::string& attribute, const AttributeFormat& f, bool quantization) {
  const int kF = TINYGLTF_COMPONENT_TYPE_FLOAT, kB = TINYGLTF_COMPONENT_TYPE_BYTE,
            kUB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, kS = TINYGLTF_COMPONENT_TYPE_SHORT,
            kUS = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const bool isFloat = f.componentType == kF && !f.normalized;
  const bool smallInt =
      f.componentType == kB || f.componentType == kUB || f.componentType == kS || f.componentType == kUS;
  const bool signedNormalized = f.normalized && (f.componentType == kB || f.componentType == kS);
  const bool unsignedNormalized = f.normalized && (f.componentType == kUB || f.componentType == kUS);
  if (attribute == "POSITION") return f.type == TINYGLTF_TYPE_VEC3 && (isFloat || (quantization && smallInt));
  if (attribute == "NORMAL") return f.type == TINYGLTF_TYPE_VEC3 && (isFloat || (quantization && signedNormalized));
  if (attribute.rfind("TEXCOORD_", 0) == 0)
    return f.type == TINYGLTF_TYPE_VEC2 && (isFloat || unsignedNormalized || (quantization && smallInt));
  if (attribute.rfind("COLOR_", 0) == 0)
    return (f.type == TINYGLTF_TYPE_VEC3 || f.type == TINYGLTF_TYPE_VEC4) && (isFloat || unsignedNormalized);
  return true;  // attributes this renderer does not read
}

std::string allowedFormatsText(const std::string& attribute, bool quantization) {
  if (attribute == "POSITION")
    return quantization ? "VEC3 FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT (KHR_mesh_quantization)"
                        : "VEC3 FLOAT (other types need KHR_mesh_quantization)";
  if (attribute == "NORMAL")
    return quantization ? "VEC3 FLOAT, or normalized BYTE or SHORT (KHR_mesh_quantization)"
                        : "VEC3 FLOAT (other types need KHR_mesh_quantization)";
  if (attribute.rfind("TEXCOORD_", 0) == 0)
    return quantization ? "VEC2 FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT (KHR_mesh_quantization)"
                        : "VEC2 FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT";
  return "VEC3 or VEC4 FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT";
}

// First element of `count` elements of `elementSize` bytes, `stride` apart (0 = packed), at
// `offset` in bufferView `viewIndex`; fails unless every byte read lies inside the view.
const unsigned char* locate(const tinygltf::Model& model, int viewIndex, size_t offset, size_t count,
                            size_t elementSize, size_t* stride, const std::string& what) {
  size_t viewLength = 0, viewStride = 0;
  const unsigned char* data = bufferViewData(model, viewIndex, what, &viewLength, &viewStride);
  if (*stride == 0) *stride = viewStride ? viewStride : elementSize;
  if (*stride < elementSize)
    fail(what + ": bufferView " + std::to_string(viewIndex) + " has byteStride " + std::to_string(*stride) +
         ", smaller than one element (" + std::to_string(elementSize) + " bytes)");
  if (count == 0) return data;
  // Written to avoid overflow for absurd counts: last element start + size <= view length.
  const bool fits = offset <= viewLength && elementSize <= viewLength - offset &&
                    count - 1 <= (viewLength - offset - elementSize) / *stride;
  if (!fits) {
    const double needed = double(offset) + double(*stride) * double(count - 1) + double(elementSize);
    fail(what + " reads past the end of bufferView " + std::to_string(viewIndex) + ": " + std::to_string(count) +
         " elements need " + std::to_string(std::uint64_t(needed)) + " bytes, the view has " +
         std::to_string(viewLength) + " (wrong accessor count or offset?)");
  }
  return data + offset;
}

// Every element of accessor `acc` (dense data with sparse substitutions applied), each converted by
// read(bytes) to T; read(nullptr) is an element without data (all zeros). Fails on any
// out-of-bounds read.
template <typename T, typename Read>
std::vector<T> readElements(const tinygltf::Model& model, const tinygltf::Accessor& acc, size_t elementSize,
                            const std::string& what, Read read) {
  std::vector<T> out;
  if (acc.bufferView >= 0) {
    size_t stride = 0;
    const unsigned char* p = locate(model, acc.bufferView, acc.byteOffset, acc.count, elementSize, &stride, what);
    out.resize(acc.count);
    for (size_t i = 0; i < acc.count; ++i) out[i] = read(p + i * stride);
  } else {
    // No bufferView: all zeros (then usually sparse). Cap the count: nothing bounds it otherwise.
    if (acc.count > (size_t(1) << 24))
      fail(what + ": accessor count " + std::to_string(acc.count) + " is implausibly large");
    out.assign(acc.count, read(nullptr));
  }
  if (acc.sparse.isSparse) {
    const auto& s = acc.sparse;
    const size_t n = size_t(std::max(s.count, 0));
    if (n > acc.count)
      fail(what + ": the sparse substitution overrides " + std::to_string(n) + " elements, more than the accessor's " +
           std::to_string(acc.count));
    if (!isIndexType(s.indices.componentType))
      fail(what + ": sparse indices have component type " + std::to_string(s.indices.componentType) +
           ", expected an unsigned integer type");
    const size_t indexSize = componentSize(s.indices.componentType);
    size_t indexStride = indexSize, valueStride = elementSize;  // sparse data is always tightly packed
    const unsigned char* indices = locate(model, s.indices.bufferView, size_t(std::max(s.indices.byteOffset, 0)), n,
                                          indexSize, &indexStride, what + " (sparse indices)");
    const unsigned char* values = locate(model, s.values.bufferView, size_t(std::max(s.values.byteOffset, 0)), n,
                                         elementSize, &valueStride, what + " (sparse values)");
    std::uint32_t previous = 0;
    for (size_t k = 0; k < n; ++k) {
      const std::uint32_t target = readIndex(indices + k * indexSize, s.indices.componentType);
      if (target >= out.size())
        fail(what + ": sparse index " + std::to_string(target) + " is out of range (the accessor has " +
             std::to_string(out.size()) + " elements)");
      // Strictly increasing (glTF): with a repeated index, which value wins would be up to the reader.
      if (k > 0 && target <= previous)
        fail(what + ": sparse indices are not strictly increasing (" + std::to_string(target) + " after " +
             std::to_string(previous) + ")");
      previous = target;
      out[target] = read(values + k * elementSize);
    }
  }
  return out;
}

}  // namespace

size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not legal in glTF 2.0
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;  // matrices: no vertex attribute we read uses them
  }
}

const char* componentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "an invalid component type";
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "an invalid type";
  }
}

float readComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? float(*p) / 255.0f : float(*p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = static_cast<std::int8_t>(*p);
      return normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return float(v);
    }
    default:
      return 0.0f;
  }
}

bool isIndexType(int componentType) {
  return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

std::uint32_t readIndex(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

std::vector<std::uint32_t> triangulate(int mode, const std::vector<std::uint32_t>& idx) {
  std::vector<std::uint32_t> tris;
  const size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    tris.assign(idx.begin(), idx.begin() + std::ptrdiff_t(n / 3 * 3));
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP && n >= 3) {
    tris.reserve(3 * (n - 2));
    for (size_t i = 0; i + 2 < n; ++i) {
      tris.push_back(idx[i]);
      tris.push_back(idx[i + 1 + i % 2]);
      tris.push_back(idx[i + 2 - i % 2]);
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN && n >= 3) {
    tris.reserve(3 * (n - 2));
    for (size_t i = 0; i + 2 < n; ++i) {
      tris.push_back(idx[i + 1]);
      tris.push_back(idx[i + 2]);
      tris.push_back(idx[0]);
    }
  }
  return tris;
}

const tinygltf::Accessor& accessor(const tinygltf::Model& model, int index, const std::string& what) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    fail(what + " refers to accessor " + std::to_string(index) + ", but the file has " +
         std::to_string(model.accessors.size()) + " accessors");
  return model.accessors[index];
}

const unsigned char* bufferViewData(const tinygltf::Model& model, int index, const std::string& what,
                                    size_t* byteLength, size_t* byteStride) {
  if (index < 0 || size_t(index) >= model.bufferViews.size())
    fail(what + " refers to bufferView " + std::to_string(index) + ", but the file has " +
         std::to_string(model.bufferViews.size()) + " bufferViews");
  const tinygltf::BufferView& view = model.bufferViews[index];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    fail("bufferView " + std::to_string(index) + " refers to buffer " + std::to_string(view.buffer) +
         ", but the file has " + std::to_string(model.buffers.size()) + " buffers");
  const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail("bufferView " + std::to_string(index) + " (bytes " + std::to_string(view.byteOffset) + ".." +
         std::to_string(view.byteOffset + view.byteLength) + ") extends past the end of buffer " +
         std::to_string(view.buffer) + " (" + std::to_string(data.size()) + " bytes; truncated?)");
  *byteLength = view.byteLength;
  if (byteStride) *byteStride = view.byteStride;
  return data.data() + view.byteOffset;
}

template <int N>
std::vector<glm::vec<N, float>> readAccessor(const tinygltf::Model& model, int index, const std::string& what) {
  const tinygltf::Accessor& acc = accessor(model, index, what);
  const std::string where = what + " (accessor " + std::to_string(index) + ")";
  if (componentCount(acc.type) != N)
    fail(where + " has " + std::to_string(componentCount(acc.type)) + " components per element, expected " +
         std::to_string(N));
  const size_t size = componentSize(acc.componentType);
  if (size == 0) fail(where + " has unsupported component type " + std::to_string(acc.componentType));
  if (acc.normalized &&
      (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    fail(where + " is normalized with component type " + componentTypeName(acc.componentType) +
         " (only byte and short types can be normalized)");
  const int type = acc.componentType;
  const bool normalized = acc.normalized;
  return readElements<glm::vec<N, float>>(model, acc, N * size, where, [&](const unsigned char* p) {
    glm::vec<N, float> v(0.0f);
    if (p)
      for (int c = 0; c < N; ++c) v[c] = readComponent(p + c * size, type, normalized);
    return v;
  });
}
template std::vector<glm::vec1> readAccessor<1>(const tinygltf::Model&, int, const std::string&);
template std::vector<glm::vec2> readAccessor<2>(const tinygltf::Model&, int, const std::string&);
template std::vector<glm::vec3> readAccessor<3>(const tinygltf::Model&, int, const std::string&);
template std::vector<glm::vec4> readAccessor<4>(const tinygltf::Model&, int, const std::string&);

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& what) {
  const tinygltf::Accessor& acc = accessor(model, index, what);
  const std::string where = what + " (accessor " + std::to_string(index) + ")";
  if (acc.type != TINYGLTF_TYPE_SCALAR || !isIndexType(acc.componentType))
    fail(where + " must be SCALAR unsigned byte/short/int, got type " + std::to_string(acc.type) + " component type " +
         std::to_string(acc.componentType));
  if (acc.bufferView >= 0 && size_t(acc.bufferView) < model.bufferViews.size() &&
      model.bufferViews[acc.bufferView].byteStride != 0)
    fail(where + ": its bufferView " + std::to_string(acc.bufferView) +
         " has a byteStride, which index data must not have (indices are tightly packed)");
  const int type = acc.componentType;
  return readElements<std::uint32_t>(model, acc, componentSize(type), where,
                                     [&](const unsigned char* p) { return p ? readIndex(p, type) : 0u; });
}

template <int N>
std::vector<glm::vec<N, float>> readAttribute(const tinygltf::Model& model, int accessorIndex, const std::string& name,
                                              const std::string& what, size_t expectedCount, bool quantization) {
  const std::string where = what + " " + name;
  const tinygltf::Accessor& acc = accessor(model, accessorIndex, where);
  if (!allowedFormat(name, {acc.type, acc.componentType, acc.normalized}, quantization))
    fail(where + " (accessor " + std::to_string(accessorIndex) + ") is " + typeName(acc.type) + " " +
         (acc.normalized ? "normalized " : "") + componentTypeName(acc.componentType) + "; glTF allows " +
         allowedFormatsText(name, quantization));
  std::vector<glm::vec<N, float>> values = readAccessor<N>(model, accessorIndex, where);
  if (expectedCount != size_t(-1) && values.size() != expectedCount)
    fail(what + ": " + name + " has " + std::to_string(values.size()) + " elements but POSITION has " +
         std::to_string(expectedCount));
  for (size_t v = 0; v < values.size(); ++v)
    if (!finiteVec(values[v]))
      fail(what + ": " + name + " of vertex " + std::to_string(v) + " is not finite (NaN or Inf)");
  return values;
}
template std::vector<glm::vec2> readAttribute<2>(const tinygltf::Model&, int, const std::string&, const std::string&,
                                                 size_t, bool);
template std::vector<glm::vec3> readAttribute<3>(const tinygltf::Model&, int, const std::string&, const std::string&,
                                                 size_t, bool);
template std::vector<glm::vec4> readAttribute<4>(const tinygltf::Model&, int, const std::string&, const std::string&,
                                                 size_t, bool);

std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessorIndex, const std::string& what,
                                  size_t expectedCount, bool quantization) {
  const tinygltf::Accessor& acc = accessor(model, accessorIndex, what + " COLOR_0");
  if (acc.type != TINYGLTF_TYPE_VEC3)  // VEC4, or any other type for readAttribute to word the error
    return readAttribute<4>(model, accessorIndex, "COLOR_0", what, expectedCount, quantization);
  const std::vector<glm::vec3> rgb =
      readAttribute<3>(model, accessorIndex, "COLOR_0", what, expectedCount, quantization);
  std::vector<glm::vec4> rgba(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) rgba[i] = glm::vec4(rgb[i], 1.0f);
  return rgba;
}

}  // namespace lgh::gltf
