// gl::RadixSort against std::stable_sort: random 30-bit keys with many duplicates, values the pairs'
// original places (so stability shows), at sizes around the block (1024) and past a million; the same
// result on every run; an odd number of passes (12-bit keys) and keys of all 32 bits.
#include "render/gl/radix_sort.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "gl_test_env.h"

namespace lgh::test {
namespace {

class RadixSortTest : public GLTest {};

struct Pairs {
  std::vector<GLuint> keys, values;
};

// count keys in [0, 2^bits) drawn from `distinct` random values, so that equal keys are common.
Pairs randomPairs(size_t count, int bits, size_t distinct, uint32_t seed) {
  std::mt19937 rng(seed);
  const uint64_t range = uint64_t(1) << bits;
  std::vector<GLuint> pool(distinct);
  for (GLuint& k : pool) k = GLuint(rng() % range);
  Pairs p;
  p.keys.resize(count);
  p.values.resize(count);
  for (size_t i = 0; i < count; ++i) p.keys[i] = pool[rng() % distinct], p.values[i] = GLuint(i);
  return p;
}

Pairs stableSorted(const Pairs& in) {
  std::vector<size_t> order(in.keys.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return in.keys[a] < in.keys[b]; });
  Pairs out;
  for (size_t i : order) out.keys.push_back(in.keys[i]), out.values.push_back(in.values[i]);
  return out;
}

Pairs gpuSorted(gl::RadixSort& sort, const Pairs& in, int bits) {
  const gl::Buffer keys = gl::Buffer::fromVector({"test", "data"}, in.keys),
                   values = gl::Buffer::fromVector({"test", "data"}, in.values);
  sort.sort(keys, values, in.keys.size(), bits);
  return {keys.download<GLuint>(in.keys.size()), values.download<GLuint>(in.keys.size())};
}

TEST_F(RadixSortTest, EqualsStableSortOfThirtyBitKeysWithDuplicates) {
  gl::RadixSort sort("test");
  for (size_t count : {size_t(1), size_t(2), size_t(1000), size_t(1024), size_t(1025), (size_t(1) << 20) + 3}) {
    SCOPED_TRACE("count " + std::to_string(count));
    const Pairs in = randomPairs(count, 30, std::max<size_t>(count / 8, 1), uint32_t(count));
    const Pairs expected = stableSorted(in);
    const Pairs first = gpuSorted(sort, in, 30);
    EXPECT_EQ(first.keys, expected.keys);
    EXPECT_EQ(first.values, expected.values) << "equal keys must keep their order";
    if (count > 2) {  // the same input again: the same output, bit for bit
      const Pairs second = gpuSorted(sort, in, 30);
      EXPECT_EQ(second.values, first.values);
    }
  }
}

TEST_F(RadixSortTest, OddPassCountsAndFullWidthKeys) {
  gl::RadixSort sort("test");
  for (int bits : {12, 32}) {
    SCOPED_TRACE("bits " + std::to_string(bits));
    const Pairs in = randomPairs(5000, bits, 700, uint32_t(bits));
    const Pairs expected = stableSorted(in);
    const Pairs got = gpuSorted(sort, in, bits);
    EXPECT_EQ(got.keys, expected.keys);
    EXPECT_EQ(got.values, expected.values);
  }
}

}  // namespace
}  // namespace lgh::test
