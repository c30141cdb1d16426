#include "bench/common/table.h"

#include <algorithm>
#include <cmath>

namespace lgh::bench {

void TextTable::print(std::FILE* out) const {
  std::vector<size_t> widths;
  for (const auto& row : rows_) {
    widths.resize(std::max(widths.size(), row.size()), 0);
    for (size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  for (size_t r = 0; r < rows_.size(); ++r) {
    std::string line = "  ";
    for (size_t c = 0; c < rows_[r].size(); ++c) {
      const std::string& cell = rows_[r][c];
      const std::string pad(widths[c] - cell.size(), ' ');
      line += c == 0 ? cell + pad : "  " + pad + cell;
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::fprintf(out, "%s\n", line.c_str());
    if (r == 0) {  // a rule under the headers
      size_t total = 0;
      for (size_t w : widths) total += w + 2;
      std::fprintf(out, "  %s\n", std::string(total - 2, '-').c_str());
    }
  }
}

std::string formatCount(size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string formatMs(double ms) {
  if (!std::isfinite(ms)) return "-";
  char buffer[32];
  if (ms >= 1000) return formatCount(size_t(std::llround(ms)));
  std::snprintf(buffer, sizeof buffer, ms >= 100 ? "%.0f" : ms >= 10 ? "%.1f" : "%.2f", ms);
  return buffer;
}

std::string formatSpread(const Spread& s) {
  const std::string median = formatMs(s.median), low = formatMs(s.min), high = formatMs(s.max);
  return low == high ? median : median + " (" + low + "-" + high + ")";
}

std::string formatRatio(double ratio) {
  if (!std::isfinite(ratio)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, ratio >= 100 ? "%.0fx" : ratio >= 1 ? "%.1fx" : "%.2fx", ratio);
  return buffer;
}

std::string shortCount(size_t n) {
  char buffer[32];
  if (n >= 1000000)
    std::snprintf(buffer, sizeof buffer, "%gM", double(n) / 1e6);
  else if (n >= 1000)
    std::snprintf(buffer, sizeof buffer, "%gK", double(n) / 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%zu", n);
  return buffer;
}

std::string formatMegabytes(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", double(bytes) / 1e6);
  return text;
}

}  // namespace lgh::bench
