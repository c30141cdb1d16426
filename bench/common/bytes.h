#pragma once
// Plain values and vectors of them as bytes, and back: the reference's tile files
// (bench/reference/reference_tiles.h) and what ranks send each other (bench/reference/reference_ranks.h). The same
// build reads what it wrote (no byte-order or versioning concerns beyond the files' own magic and key); every read
// checks that its bytes are there, so a short or malformed input fails, never overreads.

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace lgh::bench {

class ByteWriter {
 public:
  template <typename T>
  void pod(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  template <typename T>
  void vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(std::uint64_t(values.size()));
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void string(const std::string& s) {
    pod(std::uint64_t(s.size()));
    bytes_ += s;
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  explicit ByteReader(std::string&&) = delete;  // it keeps a reference: not to a temporary
  template <typename T>
  bool pod(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (bytes_.size() - at_ < sizeof value) return false;
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return true;
  }
  template <typename T>
  bool vector(std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t n = 0;
    if (!pod(n) || n > (bytes_.size() - at_) / sizeof(T)) return false;
    values.resize(size_t(n));
    if (n > 0) std::memcpy(values.data(), bytes_.data() + at_, size_t(n) * sizeof(T));
    at_ += size_t(n) * sizeof(T);
    return true;
  }
  bool string(std::string& s) {
    std::uint64_t n = 0;
    if (!pod(n) || n > bytes_.size() - at_) return false;
    s.assign(bytes_, at_, size_t(n));
    at_ += size_t(n);
    return true;
  }
  bool atEnd() const { return at_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

}  // namespace lgh::bench
