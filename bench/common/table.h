#pragma once
// Aligned text tables for the benchmarks' stdout, and the number formats they share.

#include <cstdio>
#include <string>
#include <vector>

#include "bench/common/stats.h"

namespace lgh::bench {

// Columns sized to their widest cell; the first column is left-aligned (labels), the others
// right-aligned (numbers). Cells are ASCII so that byte length is display width.
class TextTable {
 public:
  explicit TextTable(std::vector<std::string> headers) : rows_{std::move(headers)} {}
  void addRow(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  void print(std::FILE* out) const;

 private:
  std::vector<std::vector<std::string>> rows_;  // rows_[0]: the headers
};

std::string formatCount(size_t n);          // 1,000,000
std::string formatMs(double ms);            // 3 significant digits down to 0.01: 0.42, 12.1, 2,110
std::string formatSpread(const Spread& s);  // "12.1 (11.9-13.0)"; "12.1" when min == max
std::string formatRatio(double ratio);      // "174x", "4.6x", "0.98x"
std::string shortCount(size_t n);           // 1K, 100K, 1M, 4.5M: for labels
std::string formatMegabytes(size_t bytes);  // MB, two decimals: 0.03, 12.40, 1024.00

}  // namespace lgh::bench
