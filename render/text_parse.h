#pragma once
// Whole-string number parsing for settings, scripts and option values: "3x", "" and integers out of
// the type's range are errors, not 3, 0 or a wrapped value.

#include <cstdlib>
#include <limits>
#include <string>
#include <type_traits>

namespace lgh {

template <typename T>
bool parseNumber(const std::string& text, T& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  if constexpr (std::is_integral_v<T>) {
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (v < (long long)std::numeric_limits<T>::min() || v > (long long)std::numeric_limits<T>::max()) return false;
    out = T(v);
  } else {
    out = T(std::strtod(text.c_str(), &end));
  }
  return *end == '\0';
}

}  // namespace lgh
