#include "bench/reference/reference_tiles.h"

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>

#include "bench/common/bytes.h"

namespace lgh::reference {
namespace {

namespace fs = std::filesystem;

constexpr char kTileMagic[8] = {'L', 'G', 'H', 'T', 'I', 'L', 'E', '1'};

}  // namespace

TileGrid::Rect TileGrid::rect(int tile) const {
  const int cx = tile % columns(), cy = tile / columns();
  return {cx * size, cy * size, std::min(width, (cx + 1) * size), std::min(height, (cy + 1) * size)};
}

std::vector<std::uint32_t> TileGrid::pixelsOf(int tile, const std::vector<std::uint32_t>& pixels) const {
  const Rect r = rect(tile);
  std::vector<std::uint32_t> inside;
  for (int y = r.y0; y < r.y1; ++y) {
    // The row's run of the ascending list: [y * width + x0, y * width + x1).
    const std::uint32_t first = std::uint32_t(y) * std::uint32_t(width) + std::uint32_t(r.x0);
    const std::uint32_t last = first + std::uint32_t(r.x1 - r.x0);
    auto it = std::lower_bound(pixels.begin(), pixels.end(), first);
    for (; it != pixels.end() && *it < last; ++it) inside.push_back(*it);
  }
  return inside;
}

std::string TileGrid::label(int tile) const {
  const Rect r = rect(tile);
  return "tile " + std::to_string(tile) + " (x " + std::to_string(r.x0) + "-" + std::to_string(r.x1 - 1) + ", y " +
         std::to_string(r.y0) + "-" + std::to_string(r.y1 - 1) + ")";
}

TileStore::TileStore(const fs::path& cacheDir, std::string description, TileGrid grid)
    : description_(std::move(description)), grid_(grid) {
  // The tile size is part of what the files mean: another size is another folder.
  description_ += "tiles " + std::to_string(grid_.size) + "\n";
  dir_ = cacheDir / ("tiles-" + hex64(hashBytes(description_.data(), description_.size())));
}

fs::path TileStore::file(int tile) const { return dir_ / ("tile-" + std::to_string(tile) + ".bin"); }

std::optional<ReferenceImage> TileStore::load(int tile, const std::vector<std::uint32_t>& pixels,
                                              std::string* why) const {
  auto fail = [&](const std::string& reason) -> std::optional<ReferenceImage> {
    if (why) *why = file(tile).string() + ": " + reason;
    return std::nullopt;
  };
  if (why) why->clear();
  std::ifstream in(file(tile), std::ios::binary);
  if (!in) return std::nullopt;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < sizeof kTileMagic + sizeof(std::uint64_t)) return fail("truncated");
  std::uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + bytes.size() - sizeof checksum, sizeof checksum);
  const std::string body = bytes.substr(0, bytes.size() - sizeof checksum);
  if (std::memcmp(body.data(), kTileMagic, sizeof kTileMagic) != 0) return fail("not a reference tile");
  if (hashBytes(body.data(), body.size()) != checksum) return fail("checksum mismatch (truncated or corrupt)");
  bench::ByteReader r(body);
  char magic[8];
  std::string description;
  int index = -1;
  TileGrid::Rect rect;
  ReferenceImage part;
  const bool read =
      r.pod(magic) && r.string(description) && r.pod(index) && r.pod(rect) && readReference(r, part) && r.atEnd();
  if (!read) return fail("malformed");
  if (description != description_) return fail("of another reference");
  if (index != tile || !(rect == grid_.rect(tile)) || part.width != grid_.width || part.height != grid_.height)
    return fail("of another tile");
  if (part.pixels != grid_.pixelsOf(tile, pixels) || part.unshadowed.size() != part.pixels.size() ||
      part.shadowed.size() != part.pixels.size())  // the references are shadowed ones
    return fail("of other pixels");
  return part;
}

void TileStore::store(int tile, const ReferenceImage& part) const {
  std::error_code error;
  fs::create_directories(dir_, error);
  if (error) throw std::runtime_error(dir_.string() + ": cannot create the tile folder: " + error.message());
  bench::ByteWriter w;
  w.bytes().append(kTileMagic, sizeof kTileMagic);
  w.string(description_);
  w.pod(tile);
  w.pod(grid_.rect(tile));
  writeReference(w, part);
  w.pod(hashBytes(w.bytes().data(), w.bytes().size()));
  const fs::path path = file(tile);
  // Unique per process and host-independent enough: ranks never write the same tile at once.
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(temporary.string() + ": cannot open for writing");
    out.write(w.bytes().data(), std::streamsize(w.bytes().size()));
    out.flush();
    if (!out) throw std::runtime_error(temporary.string() + ": write failed");
  }
  fs::rename(temporary, path, error);
  if (error) {
    fs::remove(temporary);
    throw std::runtime_error(path.string() + ": cannot move the tile into place: " + error.message());
  }
}

void TileStore::remove() const {
  std::error_code error;
  fs::remove_all(dir_, error);
}

void writeReference(bench::ByteWriter& w, const ReferenceImage& image) {
  w.pod(image.width);
  w.pod(image.height);
  w.vector(image.pixels);
  w.vector(image.unshadowed);
  w.vector(image.shadowed);
  w.pod(image.seconds);
  w.pod(image.pairs);
  w.pod(image.rays);
  w.pod(image.threads);
  w.pod(std::uint64_t(image.lightCount));
}

bool readReference(bench::ByteReader& r, ReferenceImage& image) {
  std::uint64_t lightCount = 0;
  const bool ok = r.pod(image.width) && r.pod(image.height) && r.vector(image.pixels) && r.vector(image.unshadowed) &&
                  r.vector(image.shadowed) && r.pod(image.seconds) && r.pod(image.pairs) && r.pod(image.rays) &&
                  r.pod(image.threads) && r.pod(lightCount);
  image.lightCount = size_t(lightCount);
  return ok;
}

ReferenceImage assembleTiles(const TileGrid& grid, const std::vector<std::uint32_t>& pixels,
                             const std::vector<ReferenceImage>& parts) {
  if (int(parts.size()) != grid.count()) throw std::invalid_argument("assembleTiles: one part per tile expected");
  const size_t pixelCount = size_t(grid.width) * size_t(grid.height);
  // Where each image pixel's sums are: (part, index in it).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> where(pixelCount, {~0u, ~0u});
  bool shadowed = true;
  ReferenceImage out;
  out.width = grid.width;
  out.height = grid.height;
  out.pixels = pixels;
  for (size_t t = 0; t < parts.size(); ++t) {
    const ReferenceImage& part = parts[t];
    if (part.unshadowed.size() != part.pixels.size() ||
        (!part.shadowed.empty() && part.shadowed.size() != part.pixels.size()))
      throw std::invalid_argument("assembleTiles: a part's sums do not match its pixels");
    for (size_t i = 0; i < part.pixels.size(); ++i) {
      if (part.pixels[i] >= pixelCount || where[part.pixels[i]].first != ~0u)
        throw std::invalid_argument("assembleTiles: a pixel outside the image or in two tiles");
      where[part.pixels[i]] = {std::uint32_t(t), std::uint32_t(i)};
    }
    shadowed = shadowed && (part.pixels.empty() || !part.shadowed.empty());
    out.pairs += part.pairs;
    out.rays += part.rays;
    out.lightCount = std::max(out.lightCount, part.lightCount);
  }
  out.unshadowed.reserve(pixels.size());
  if (shadowed) out.shadowed.reserve(pixels.size());
  size_t placed = 0;
  for (std::uint32_t p : pixels) {
    const auto [t, i] = p < pixelCount ? where[p] : std::pair<std::uint32_t, std::uint32_t>{~0u, ~0u};
    if (t == ~0u) throw std::invalid_argument("assembleTiles: pixel " + std::to_string(p) + " is in no tile");
    out.unshadowed.push_back(parts[t].unshadowed[i]);
    if (shadowed) out.shadowed.push_back(parts[t].shadowed[i]);
    ++placed;
  }
  size_t given = 0;
  for (const ReferenceImage& part : parts) given += part.pixels.size();
  if (given != placed) throw std::invalid_argument("assembleTiles: the tiles hold pixels that are not asked for");
  return out;
}

}  // namespace lgh::reference
