#include "bench/common/npy.h"

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

namespace lgh::bench {

void writeNpy(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgb) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(height) + ", " +
                       std::to_string(width) + ", 3), }";
  const size_t unpadded = 10 + header.size() + 1;  // magic, version, length, header, newline
  header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  out.write("\x93NUMPY\x01\x00", 8);
  const std::uint16_t length = std::uint16_t(header.size());
  const char le[2] = {char(length & 0xff), char(length >> 8)};
  out.write(le, 2);
  out.write(header.data(), std::streamsize(header.size()));
  out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace lgh::bench
