// glTF accessor decoding (render/scene/gltf_accessors.h) on hand-made buffers: no file, no parser,
// no GL. Each test builds the few tinygltf objects it needs and checks values or the exact message.
#include "render/scene/gltf_accessors.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "render/scene/gltf_checks.h"

namespace lgh::test {
namespace {

using gltf::FileProblem;

constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE, kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
              kShort = TINYGLTF_COMPONENT_TYPE_SHORT, kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
              kUnsignedInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

// Appends the bytes of `values` to `bytes`.
template <typename T>
void append(std::vector<unsigned char>& bytes, std::initializer_list<T> values) {
  for (const T& v : values) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    bytes.insert(bytes.end(), b, b + sizeof(T));
  }
}

// A model with one buffer, to which tests add views and accessors.
struct ModelBuilder {
  tinygltf::Model model;
  explicit ModelBuilder(std::vector<unsigned char> bytes) {
    model.buffers.emplace_back();
    model.buffers[0].data = std::move(bytes);
  }
  int view(size_t byteOffset, size_t byteLength, size_t byteStride = 0) {
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = byteOffset;
    v.byteLength = byteLength;
    v.byteStride = byteStride;
    model.bufferViews.push_back(v);
    return int(model.bufferViews.size()) - 1;
  }
  int accessor(int bufferView, int componentType, int type, size_t count, size_t byteOffset = 0,
               bool normalized = false) {
    tinygltf::Accessor a;
    a.bufferView = bufferView;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.byteOffset = byteOffset;
    a.normalized = normalized;
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
  }
  // Makes accessor `index` sparse: `count` substitutions, indices and values tightly packed in the given views.
  void sparse(int index, int count, int indexView, int indexType, int valueView) {
    auto& s = model.accessors[index].sparse;
    s.isSparse = true;
    s.count = count;
    s.indices.bufferView = indexView;
    s.indices.byteOffset = 0;
    s.indices.componentType = indexType;
    s.values.bufferView = valueView;
    s.values.byteOffset = 0;
  }
};

// The message of the FileProblem `f` throws ("" when it throws none).
template <typename F>
std::string problemOf(F f) {
  try {
    f();
  } catch (const FileProblem& e) {
    return e.what();
  }
  return "";
}

TEST(GltfAccessors, NormalizedIntegersFollowTheSpecification) {
  const auto read = [](auto value, int componentType, bool normalized) {
    unsigned char b[sizeof(value)];
    std::memcpy(b, &value, sizeof(value));
    return gltf::readComponent(b, componentType, normalized);
  };
  EXPECT_EQ(read(std::uint8_t(255), kUnsignedByte, true), 1.0f);
  EXPECT_EQ(read(std::uint8_t(0), kUnsignedByte, true), 0.0f);
  EXPECT_FLOAT_EQ(read(std::uint8_t(51), kUnsignedByte, true), 0.2f);
  EXPECT_EQ(read(std::int8_t(127), kByte, true), 1.0f);
  EXPECT_EQ(read(std::int8_t(-127), kByte, true), -1.0f);
  EXPECT_EQ(read(std::int8_t(-128), kByte, true), -1.0f);  // max(c / 127, -1): both lowest values are -1
  EXPECT_EQ(read(std::uint16_t(65535), kUnsignedShort, true), 1.0f);
  EXPECT_EQ(read(std::int16_t(32767), kShort, true), 1.0f);
  EXPECT_EQ(read(std::int16_t(-32768), kShort, true), -1.0f);
  EXPECT_EQ(read(std::int16_t(-32767), kShort, true), -1.0f);
  // Not normalized: the integer itself (KHR_mesh_quantization positions).
  EXPECT_EQ(read(std::int16_t(-32768), kShort, false), -32768.0f);
  EXPECT_EQ(read(std::uint8_t(255), kUnsignedByte, false), 255.0f);
  EXPECT_EQ(read(std::int8_t(-5), kByte, false), -5.0f);
  EXPECT_EQ(read(std::uint32_t(70000), kUnsignedInt, false), 70000.0f);
  EXPECT_EQ(read(2.5f, kFloat, false), 2.5f);
  EXPECT_EQ(read(std::uint32_t(1), 5124 /* INT: not glTF 2.0 */, false), 0.0f);
}

TEST(GltfAccessors, ComponentSizesAndCounts) {
  EXPECT_EQ(gltf::componentSize(kByte), 1u);
  EXPECT_EQ(gltf::componentSize(kUnsignedByte), 1u);
  EXPECT_EQ(gltf::componentSize(kShort), 2u);
  EXPECT_EQ(gltf::componentSize(kUnsignedShort), 2u);
  EXPECT_EQ(gltf::componentSize(kUnsignedInt), 4u);
  EXPECT_EQ(gltf::componentSize(kFloat), 4u);
  EXPECT_EQ(gltf::componentSize(TINYGLTF_COMPONENT_TYPE_DOUBLE), 0u);
  EXPECT_EQ(gltf::componentCount(TINYGLTF_TYPE_SCALAR), 1);
  EXPECT_EQ(gltf::componentCount(TINYGLTF_TYPE_VEC4), 4);
  EXPECT_EQ(gltf::componentCount(TINYGLTF_TYPE_MAT4), 0);
}

TEST(GltfAccessors, InterleavedAttributesFollowTheByteStride) {
  // After 8 bytes of something else, two vertices of 16 bytes each: a float VEC3 position (12 bytes),
  // then a normalized UNSIGNED_BYTE VEC4 colour (4 bytes).
  std::vector<unsigned char> bytes(8, 0xee);
  append<float>(bytes, {1.0f, 2.0f, 3.0f});
  append<std::uint8_t>(bytes, {255, 0, 51, 255});
  append<float>(bytes, {-4.0f, 5.0f, -6.0f});
  append<std::uint8_t>(bytes, {0, 255, 0, 0});
  ModelBuilder b(bytes);
  const int view = b.view(8, 32, 16);
  const int positions = b.accessor(view, kFloat, TINYGLTF_TYPE_VEC3, 2);
  const int colors = b.accessor(view, kUnsignedByte, TINYGLTF_TYPE_VEC4, 2, 12, true);

  const std::vector<glm::vec3> p = gltf::readAccessor<3>(b.model, positions, "POSITION");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(p[1], glm::vec3(-4, 5, -6));
  const std::vector<glm::vec4> c = gltf::readAccessor<4>(b.model, colors, "COLOR_0");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].x, 1.0f);
  EXPECT_FLOAT_EQ(c[0].z, 0.2f);
  EXPECT_EQ(c[1], glm::vec4(0, 1, 0, 0));
}

TEST(GltfAccessors, SparseValuesReplaceDenseOnes) {
  std::vector<unsigned char> bytes;
  append<float>(bytes, {0, 0, 1, 1, 2, 2, 3, 3});  // 4 dense VEC2s at 0
  append<std::uint8_t>(bytes, {1, 3, 0, 0});       // sparse indices at 32 (padded to 4)
  append<float>(bytes, {10, 11, 30, 31});          // sparse values at 36
  ModelBuilder b(bytes);
  const int dense = b.view(0, 32), indices = b.view(32, 2), values = b.view(36, 16);
  const int withData = b.accessor(dense, kFloat, TINYGLTF_TYPE_VEC2, 4);
  b.sparse(withData, 2, indices, kUnsignedByte, values);
  EXPECT_EQ(gltf::readAccessor<2>(b.model, withData, "TEXCOORD_0"),
            (std::vector<glm::vec2>{{0, 0}, {10, 11}, {2, 2}, {30, 31}}));

  // Without a bufferView the dense elements are zeros.
  const int zeros = b.accessor(-1, kFloat, TINYGLTF_TYPE_VEC2, 4);
  b.sparse(zeros, 2, indices, kUnsignedByte, values);
  EXPECT_EQ(gltf::readAccessor<2>(b.model, zeros, "TEXCOORD_0"),
            (std::vector<glm::vec2>{{0, 0}, {10, 11}, {0, 0}, {30, 31}}));
}

TEST(GltfAccessors, SparseIndicesOutOfOrderOrRangeFail) {
  std::vector<unsigned char> bytes;
  append<std::uint16_t>(bytes, {3, 1, 7, 0});  // indices "3, 1" at 0, "7" at 4
  append<float>(bytes, {5, 6});                // values at 8
  ModelBuilder b(bytes);
  const int decreasing = b.view(0, 4), outOfRange = b.view(4, 2), values = b.view(8, 8);
  const int a = b.accessor(-1, kUnsignedInt, TINYGLTF_TYPE_SCALAR, 4);
  b.sparse(a, 2, decreasing, kUnsignedShort, values);
  EXPECT_EQ(problemOf([&] { gltf::readIndices(b.model, a, "what"); }),
            "what (accessor 0): sparse indices are not strictly increasing (1 after 3)");
  b.sparse(a, 1, outOfRange, kUnsignedShort, values);
  EXPECT_EQ(problemOf([&] { gltf::readIndices(b.model, a, "what"); }),
            "what (accessor 0): sparse index 7 is out of range (the accessor has 4 elements)");
}

TEST(GltfAccessors, IndicesOfEachType) {
  std::vector<unsigned char> bytes;
  append<std::uint8_t>(bytes, {0, 1, 2, 255});
  append<std::uint16_t>(bytes, {0, 1, 2, 65535});
  append<std::uint32_t>(bytes, {0, 1, 2, 4000000000u});
  ModelBuilder b(bytes);
  const int u8 = b.accessor(b.view(0, 4), kUnsignedByte, TINYGLTF_TYPE_SCALAR, 4);
  const int u16 = b.accessor(b.view(4, 8), kUnsignedShort, TINYGLTF_TYPE_SCALAR, 4);
  const int u32 = b.accessor(b.view(12, 16), kUnsignedInt, TINYGLTF_TYPE_SCALAR, 4);
  const int u32Offset = b.accessor(b.view(12, 16), kUnsignedInt, TINYGLTF_TYPE_SCALAR, 2, 8);
  EXPECT_EQ(gltf::readIndices(b.model, u8, "i"), (std::vector<std::uint32_t>{0, 1, 2, 255}));
  EXPECT_EQ(gltf::readIndices(b.model, u16, "i"), (std::vector<std::uint32_t>{0, 1, 2, 65535}));
  EXPECT_EQ(gltf::readIndices(b.model, u32, "i"), (std::vector<std::uint32_t>{0, 1, 2, 4000000000u}));
  EXPECT_EQ(gltf::readIndices(b.model, u32Offset, "i"), (std::vector<std::uint32_t>{2, 4000000000u}));

  // Index data is tightly packed: a byteStride on its view is an error, not a hint.
  b.model.bufferViews[b.model.accessors[u16].bufferView].byteStride = 4;
  EXPECT_EQ(problemOf([&] { gltf::readIndices(b.model, u16, "mesh 0 primitive 0 indices"); }),
            "mesh 0 primitive 0 indices (accessor 1): its bufferView 1 has a byteStride, which index data must not "
            "have (indices are tightly packed)");
}

TEST(GltfAccessors, TrianglesStripsAndFans) {
  using Indices = std::vector<std::uint32_t>;
  EXPECT_EQ(gltf::triangulate(TINYGLTF_MODE_TRIANGLES, {0, 1, 2, 3, 4, 5, 6}), (Indices{0, 1, 2, 3, 4, 5}));
  // Strip: triangle i is {v_i, v_i+1+i%2, v_i+2-i%2}: every other one swaps its last two corners, so all keep
  // the first one's winding.
  EXPECT_EQ(gltf::triangulate(TINYGLTF_MODE_TRIANGLE_STRIP, {10, 11, 12, 13, 14}),
            (Indices{10, 11, 12, 11, 13, 12, 12, 13, 14}));
  EXPECT_EQ(gltf::triangulate(TINYGLTF_MODE_TRIANGLE_FAN, {10, 11, 12, 13}), (Indices{11, 12, 10, 12, 13, 10}));
  EXPECT_TRUE(gltf::triangulate(TINYGLTF_MODE_TRIANGLE_STRIP, {0, 1}).empty());
  EXPECT_TRUE(gltf::triangulate(TINYGLTF_MODE_TRIANGLE_FAN, {0, 1}).empty());
  EXPECT_TRUE(gltf::triangulate(TINYGLTF_MODE_POINTS, {0, 1, 2}).empty());
}

TEST(GltfAccessors, ReadsPastTheDataFailNamingWhatAndWhere) {
  std::vector<unsigned char> bytes;
  append<float>(bytes, {0, 1, 2, 3, 4, 5, 6, 7});  // 32 bytes
  ModelBuilder b(bytes);
  const int view = b.view(0, 32);
  // Three VEC3s need 36 bytes.
  const int tooMany = b.accessor(view, kFloat, TINYGLTF_TYPE_VEC3, 3);
  EXPECT_EQ(problemOf([&] { gltf::readAccessor<3>(b.model, tooMany, "mesh 0 primitive 0 POSITION"); }),
            "mesh 0 primitive 0 POSITION (accessor 0) reads past the end of bufferView 0: 3 elements need 36 bytes, "
            "the view has 32 (wrong accessor count or offset?)");
  // Two fit, but not from byte 12.
  const int offset = b.accessor(view, kFloat, TINYGLTF_TYPE_VEC3, 2, 12);
  EXPECT_EQ(problemOf([&] { gltf::readAccessor<3>(b.model, offset, "p"); }),
            "p (accessor 1) reads past the end of bufferView 0: 2 elements need 36 bytes, the view has 32 (wrong "
            "accessor count or offset?)");
  // A count so large that offset + stride * count overflows size_t must still be caught.
  const int absurd = b.accessor(view, kFloat, TINYGLTF_TYPE_VEC3, std::numeric_limits<size_t>::max() / 4);
  EXPECT_NE(problemOf([&] { gltf::readAccessor<3>(b.model, absurd, "p"); }).find("reads past the end"),
            std::string::npos);
  // A stride shorter than one element.
  b.model.bufferViews[view].byteStride = 8;
  EXPECT_EQ(problemOf([&] { gltf::readAccessor<3>(b.model, offset, "p"); }),
            "p (accessor 1): bufferView 0 has byteStride 8, smaller than one element (12 bytes)");
  // A truncated buffer: the view itself extends past it.
  b.model.buffers[0].data.resize(20);
  EXPECT_EQ(problemOf([&] { gltf::readAccessor<3>(b.model, offset, "p"); }),
            "bufferView 0 (bytes 0..32) extends past the end of buffer 0 (20 bytes; truncated?)");
  // References to what is not there.
  EXPECT_EQ(problemOf([&] { gltf::readAccessor<3>(b.model, 7, "p"); }),
            "p refers to accessor 7, but the file has 3 accessors");
  b.model.accessors[offset].bufferView = 4;
  EXPECT_EQ(problemOf([&] { gltf::readAccessor<3>(b.model, offset, "p"); }),
            "p (accessor 1) refers to bufferView 4, but the file has 1 bufferViews");
}

TEST(GltfAccessors, AttributeFormatsAreCheckedAgainstTheSpecification) {
  std::vector<unsigned char> bytes;
  append<std::int16_t>(bytes, {-32768, 0, 32767, 0});  // one normalized SHORT VEC3, padded to 8 bytes
  ModelBuilder b(bytes);
  const int position = b.accessor(b.view(0, 8), kShort, TINYGLTF_TYPE_VEC3, 1, 0, true);
  EXPECT_EQ(problemOf([&] { gltf::readAttribute<3>(b.model, position, "POSITION", "mesh 0 primitive 0", 1, false); }),
            "mesh 0 primitive 0 POSITION (accessor 0) is VEC3 normalized SHORT; glTF allows VEC3 FLOAT (other types "
            "need KHR_mesh_quantization)");
  EXPECT_EQ(gltf::readAttribute<3>(b.model, position, "POSITION", "mesh 0 primitive 0", 1, true),
            (std::vector<glm::vec3>{{-1, 0, 1}}));
  // KHR_mesh_quantization allows the same data as NORMAL; checked against POSITION's count.
  EXPECT_EQ(problemOf([&] { gltf::readAttribute<3>(b.model, position, "NORMAL", "mesh 0 primitive 0", 2, true); }),
            "mesh 0 primitive 0: NORMAL has 1 elements but POSITION has 2");
}

TEST(GltfAccessors, ColorsGetAlphaOneAndNaNsFail) {
  std::vector<unsigned char> bytes;
  append<float>(bytes, {0.5f, 0.25f, 1.0f, std::numeric_limits<float>::quiet_NaN(), 0, 0});
  ModelBuilder b(bytes);
  const int rgb = b.accessor(b.view(0, 12), kFloat, TINYGLTF_TYPE_VEC3, 1);
  const int withNaN = b.accessor(b.view(12, 12), kFloat, TINYGLTF_TYPE_VEC3, 1);
  EXPECT_EQ(gltf::readColors(b.model, rgb, "m", 1, false), (std::vector<glm::vec4>{{0.5f, 0.25f, 1.0f, 1.0f}}));
  EXPECT_EQ(problemOf([&] { gltf::readColors(b.model, withNaN, "m", 1, false); }),
            "m: COLOR_0 of vertex 0 is not finite (NaN or Inf)");
}

}  // namespace
}  // namespace lgh::test
