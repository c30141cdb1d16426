#include "bench/reference/reference_ranks.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <stdexcept>
#include <thread>

#include "bench/common/bytes.h"
#include "bench/common/progress.h"
#include "bench/common/ranks.h"

namespace lgh::bench {
namespace {

using reference::ReferenceImage;
using reference::ReferenceInput;
using reference::TileGrid;
using reference::TileStore;

// What rank 0 sends every rank before the tiles: the input, the subset and the missing tiles.
struct Work {
  ReferenceInput input;
  std::vector<std::uint32_t> pixels;
  std::vector<int> missing;
  std::string description;
  int tileSize = 32;
  bool cached = false;  // the whole reference came from the cache: `image` holds it, nothing to compute
  ReferenceImage image;
};

std::string toBytes(const Work& work) {
  ByteWriter w;
  w.pod(work.cached);
  if (work.cached) {
    reference::writeReference(w, work.image);
    return std::move(w.bytes());
  }
  w.pod(work.input.width);
  w.pod(work.input.height);
  w.vector(work.input.position);
  w.vector(work.input.normal);
  w.vector(work.input.lights);
  w.pod(work.input.clampDistance);
  w.vector(work.pixels);
  w.vector(work.missing);
  w.string(work.description);
  w.pod(work.tileSize);
  return std::move(w.bytes());
}

Work workFromBytes(const std::string& bytes) {
  Work work;
  ByteReader r(bytes);
  bool ok = r.pod(work.cached);
  if (ok && work.cached)
    ok = reference::readReference(r, work.image);
  else
    ok = ok && r.pod(work.input.width) && r.pod(work.input.height) && r.vector(work.input.position) &&
         r.vector(work.input.normal) && r.vector(work.input.lights) && r.pod(work.input.clampDistance) &&
         r.vector(work.pixels) && r.vector(work.missing) && r.string(work.description) && r.pod(work.tileSize);
  if (!ok || !r.atEnd()) throw std::runtime_error("reference: malformed work message from rank 0");
  return work;
}

unsigned threadsPerRank(const Ranks& ranks, unsigned requested) {
  if (requested > 0) return requested;
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  return std::max(1u, hardware / unsigned(std::max(1, ranks.ranksOnThisHost())));
}

}  // namespace

ReferenceImage computeTiledReference(const Ranks& ranks, const reference::OcclusionScene& occlusion,
                                     const ReferenceInput& input, const std::vector<std::uint32_t>& pixels,
                                     const std::string& description, const TiledReferenceOptions& options,
                                     TileCounts& counts) {
  if (options.tileSize < 1) throw std::invalid_argument("reference: the tile size must be >= 1");
  const bool keepTiles = !options.cacheDir.empty();
  const TileGrid grid{input.width, input.height, options.tileSize};  // rank 0's (the others' input is empty)
  counts = TileCounts{};
  counts.ranks = ranks.size();

  // Rank 0: the whole reference from the cache, or the tiles there and the ones missing.
  Work work;
  std::vector<ReferenceImage> parts;  // rank 0: one per tile
  if (ranks.root()) {
    work.description = description;
    work.tileSize = options.tileSize;
    if (keepTiles)
      if (auto whole = reference::loadReference(options.cacheDir, description)) {
        work.cached = true;
        work.image = std::move(*whole);
      }
    if (!work.cached) {
      work.input = input;
      work.pixels = pixels;
      parts.resize(size_t(grid.count()));
      const TileStore store(options.cacheDir, description, grid);
      for (int t = 0; t < grid.count(); ++t) {
        std::string why;
        std::optional<ReferenceImage> part;
        if (keepTiles) part = store.load(t, pixels, &why);
        if (part) {
          parts[size_t(t)] = std::move(*part);
          ++counts.cached;
        } else {
          work.missing.push_back(t);
          if (!why.empty()) counts.redoneWhy.push_back(why);
        }
      }
    }
  }
  std::string message = ranks.root() ? toBytes(work) : std::string();
  ranks.broadcast(message);
  if (!ranks.root()) work = workFromBytes(message);
  counts.fromCache = work.cached;
  if (work.cached) {
    counts.tiles = TileGrid{work.image.width, work.image.height, options.tileSize}.count();
    return std::move(work.image);
  }

  // Every rank: its share of the missing tiles, each stored as it completes.
  const TileGrid workGrid{work.input.width, work.input.height, work.tileSize};
  const TileStore store(options.cacheDir, work.description, workGrid);
  reference::ReferenceOptions o;
  o.threads = threadsPerRank(ranks, options.threads);
  o.progress = false;
  std::vector<int> mine;
  for (size_t i = size_t(ranks.rank()); i < work.missing.size(); i += size_t(ranks.size()))
    mine.push_back(work.missing[i]);
  ProgressBar bar(options.label + " (" + std::to_string(work.missing.size()) + " of " +
                      std::to_string(workGrid.count()) + " tiles of " + std::to_string(work.tileSize) + " px, " +
                      std::to_string(ranks.size()) + " rank" + (ranks.size() == 1 ? "" : "s") + " x " +
                      std::to_string(o.threads) + " threads; rank 0's share)",
                  double(mine.size()), options.progress && ranks.root() && !mine.empty());
  const auto start = std::chrono::steady_clock::now();
  std::string mineBytes;
  {
    ByteWriter w;
    int stored = 0;
    for (size_t i = 0; i < mine.size(); ++i) {
      const int t = mine[i];
      ReferenceImage part;
      try {
        if (t == options.failTile) throw std::runtime_error("failing as asked (--fail-tile)");
        part = reference::computePixels(occlusion, work.input, workGrid.pixelsOf(t, work.pixels), o);
        if (keepTiles) store.store(t, part);
      } catch (const std::exception& e) {
        const std::string what = "reference: " + workGrid.label(t) + " failed: " + e.what();
        if (ranks.distributed()) ranks.abort(what);
        throw std::runtime_error(what);
      }
      if (keepTiles && ++stored == options.killAfterTiles) std::raise(SIGKILL);  // the test's kill
      w.pod(t);
      reference::writeReference(w, part);
      bar.update(double(i + 1));
    }
    mineBytes = std::move(w.bytes());
  }
  bar.finish();

  // Rank 0: the parts, the image, the cache; then every rank gets the image.
  const std::vector<std::string> gathered = ranks.gather(mineBytes);
  ReferenceImage image;
  if (ranks.root()) {
    for (const std::string& bytes : gathered) {
      ByteReader r(bytes);
      while (!r.atEnd()) {
        int t = -1;
        ReferenceImage part;
        if (!r.pod(t) || t < 0 || t >= workGrid.count() || !reference::readReference(r, part))
          throw std::runtime_error("reference: malformed tile message");
        parts[size_t(t)] = std::move(part);
      }
    }
    image = reference::assembleTiles(workGrid, work.pixels, parts);
    counts.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    image.threads = o.threads * unsigned(ranks.size());
    // The thread-seconds of every tile (this run's and those an earlier run kept) over this run's
    // threads: what an uninterrupted run would have taken, so that rays / seconds stays the rate.
    double threadSeconds = 0;
    for (const ReferenceImage& part : parts) threadSeconds += part.seconds * double(part.threads);
    image.seconds = threadSeconds / double(image.threads);
    image.lightCount = work.input.lights.size();
    if (keepTiles) {
      reference::storeReference(options.cacheDir, work.description, image);
      store.remove();
    }
  }
  counts.tiles = workGrid.count();
  counts.computed = int(work.missing.size());
  counts.threadsPerRank = o.threads;
  std::string imageBytes;
  if (ranks.root()) {
    ByteWriter w;
    reference::writeReference(w, image);
    imageBytes = std::move(w.bytes());
  }
  if (ranks.distributed()) {
    ranks.broadcast(imageBytes);
    if (!ranks.root()) {
      ByteReader r(imageBytes);
      if (!reference::readReference(r, image))
        throw std::runtime_error("reference: malformed image message from rank 0");
    }
  }
  return image;
}

}  // namespace lgh::bench
