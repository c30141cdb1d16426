#include "render/gl/radix_sort.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "shared/bindings.h"

namespace lgh::gl {
namespace {
constexpr size_t kBlockSize = 1024;  // 256 threads x 4 pairs, as in glsl/radix_sort.comp
constexpr size_t kDigits = 16;       // 4 bits per pass
}  // namespace

RadixSort::RadixSort(const std::string& owner)
    : owner_(owner),
      local_(Program::compute("radix_sort.comp", {{"LGH_RADIX_LOCAL", "1"}})),
      scatter_(Program::compute("radix_sort.comp", {{"LGH_RADIX_SCATTER", "1"}})),
      prefixSum_(owner) {}

void RadixSort::release() {
  scratchKeys_ = {};
  scratchValues_ = {};
  otherKeys_ = {};
  otherValues_ = {};
  digitCounts_ = {};
  prefixSum_.release();
}

void RadixSort::sort(const Buffer& keys, const Buffer& values, size_t count, int keyBits) {
  if (count < 2 || keyBits <= 0) return;
  if (keyBits > 32) throw std::invalid_argument("RadixSort: keys have at most 32 bits, not " + std::to_string(keyBits));
  if (keys.size() < count * sizeof(GLuint) || values.size() < count * sizeof(GLuint))
    throw std::invalid_argument("RadixSort: " + std::to_string(count) + " pairs exceed the buffers");
  const size_t blocks = (count + kBlockSize - 1) / kBlockSize;
  const size_t bytes = count * sizeof(GLuint);
  const std::string scaled = "the sorted pairs";
  ensureSize(scratchKeys_, {owner_, "sort: block keys", scaled}, blocks * kBlockSize * sizeof(GLuint));
  ensureSize(scratchValues_, {owner_, "sort: block values", scaled}, blocks * kBlockSize * sizeof(GLuint));
  ensureSize(otherKeys_, {owner_, "sort: keys", scaled}, bytes);
  ensureSize(otherValues_, {owner_, "sort: values", scaled}, bytes);
  ensureSize(digitCounts_, {owner_, "sort: digit counts", scaled}, (kDigits * blocks + 1) * sizeof(GLuint));

  // A dispatch reads pairs from one side and writes them to the other, and reads or writes the counts.
  auto bindPairs = [this](const Buffer& keysIn, const Buffer& valuesIn, const Buffer& keysOut,
                          const Buffer& valuesOut) {
    keysIn.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
    valuesIn.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
    keysOut.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
    valuesOut.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
    digitCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  };
  const int passes = (keyBits + 3) / 4;
  for (int pass = 0; pass < passes; ++pass) {
    const bool fromCaller = pass % 2 == 0;
    const Buffer& inKeys = fromCaller ? keys : otherKeys_;
    const Buffer& inValues = fromCaller ? values : otherValues_;
    const Buffer& outKeys = fromCaller ? otherKeys_ : keys;
    const Buffer& outValues = fromCaller ? otherValues_ : values;
    for (Program* p : {&local_, &scatter_}) {
      p->set("count", GLuint(count));
      p->set("blocks", GLuint(blocks));
      p->set("shift", GLuint(4 * pass));
    }
    // The blocks sorted by the digit, and their digit counts.
    bindPairs(inKeys, inValues, scratchKeys_, scratchValues_);
    local_.dispatch1D(blocks * 256, 256);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    // Where each block's run of each digit goes; the total after them, which is every pair (the scatter
    // reads run lengths as differences of neighbours).
    prefixSum_.scan(digitCounts_, kDigits * blocks);
    const GLuint total = GLuint(count);
    digitCounts_.update(&total, sizeof(GLuint), kDigits * blocks * sizeof(GLuint));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    bindPairs(scratchKeys_, scratchValues_, outKeys, outValues);
    scatter_.dispatch1D(blocks * 256, 256);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  if (passes % 2 == 1) {  // the last pass wrote the other side
    glCopyNamedBufferSubData(otherKeys_.id(), keys.id(), 0, 0, GLsizeiptr(bytes));
    glCopyNamedBufferSubData(otherValues_.id(), values.id(), 0, 0, GLsizeiptr(bytes));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
}

}  // namespace lgh::gl
