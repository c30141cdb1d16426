#pragma once
// A reference computed in tiles that outlive the run (docs/design.md §13). The image is cut into square
// tiles; each tile's sums go to a file of their own as soon as the tile is done (temporary file +
// rename, so a file is whole or absent), in a folder named by the reference's cache key. A run that
// is killed at any point and started again computes only the tiles that have no file; a tile file that
// is truncated, corrupt (checksum), or of another reference, tile or pixel subset is found when it is
// read and computed again, never used. Once every tile is there, the whole reference is assembled,
// stored in the cache (bench/reference/reference.h) and the tile folder removed.
//
// Which process computes which tile is the caller's business (bench/reference/reference_ranks.h deals them to
// MPI ranks); the folder must be one that every process sees.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/common/bytes.h"
#include "bench/reference/reference.h"

namespace lgh::reference {

// The image's tiles, row by row: tile t covers columns [x0, x1) and rows [y0, y1) (rows top-down).
struct TileGrid {
  int width = 0, height = 0, size = 32;

  struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool operator==(const Rect& o) const { return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1; }
  };
  int columns() const { return (width + size - 1) / size; }
  int rows() const { return (height + size - 1) / size; }
  int count() const { return columns() * rows(); }
  Rect rect(int tile) const;
  // The pixels of `pixels` (ascending image indices) that lie in the tile, ascending.
  std::vector<std::uint32_t> pixelsOf(int tile, const std::vector<std::uint32_t>& pixels) const;
  // "tile 17 (x 64-95, y 32-63)"
  std::string label(int tile) const;
};

// One reference's tile files: <cache>/tiles-<hash of the key>/tile-<t>.bin.
class TileStore {
 public:
  TileStore(const std::filesystem::path& cacheDir, std::string description, TileGrid grid);

  const std::filesystem::path& dir() const { return dir_; }
  const TileGrid& grid() const { return grid_; }
  std::filesystem::path file(int tile) const;

  // The tile's part of the reference (computePixels over pixelsOf(tile, pixels)) when its file is
  // there, whole, and of this reference, tile and pixels; otherwise nothing, with the reason in *why
  // (left empty when there is simply no file).
  std::optional<ReferenceImage> load(int tile, const std::vector<std::uint32_t>& pixels,
                                     std::string* why = nullptr) const;
  // Written to a temporary file beside it and renamed into place. Throws std::runtime_error on failure.
  void store(int tile, const ReferenceImage& part) const;
  // The folder and every file in it (once the whole reference is in the cache).
  void remove() const;

 private:
  std::filesystem::path dir_;
  std::string description_;
  TileGrid grid_;
};

// The reference over `pixels` from its parts, one per tile in tile order (each as TileStore::load
// returns it): the sums in ascending pixel order, rays and pairs added up. Throws std::invalid_argument
// when the parts do not cover exactly `pixels`.
ReferenceImage assembleTiles(const TileGrid& grid, const std::vector<std::uint32_t>& pixels,
                             const std::vector<ReferenceImage>& parts);

// A reference (or a part of one) as bytes, as tile files and MPI messages hold it; read returns false on
// short or malformed bytes.
void writeReference(bench::ByteWriter& w, const ReferenceImage& image);
bool readReference(bench::ByteReader& r, ReferenceImage& image);

}  // namespace lgh::reference
