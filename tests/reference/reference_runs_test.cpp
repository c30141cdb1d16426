// lgh-bench reference, sweep and motion as processes (docs/design.md §13): under mpiexec -n 2 they give
// what one process gives, a run killed after some tiles and started again computes only the missing
// tiles, a corrupt or truncated tile file is computed again, and a failing rank ends the run naming the
// rank and the tile. The MPI cases skip, saying why, where lgh-bench was built without MPI.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "bench/reference/reference.h"
#include "gltf_writer.h"

namespace lgh::test {
namespace {

namespace fs = std::filesystem;

fs::path sourceDir() { return LGH_SOURCE_DIR; }

struct Process {
  int exitCode = -1;   // the exit status, or 128 + signal
  std::string output;  // stdout and stderr
  bool killed() const { return exitCode == 128 + 9 || exitCode == 9; }
};

Process run(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
  Process r;
  if (WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.exitCode = 128 + WTERMSIG(status);
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  r.output = text.str();
  return r;
}

std::string mpiexec(int ranks) {
#ifdef LGH_MPIEXEC
  return std::string(LGH_MPIEXEC) + " -n " + std::to_string(ranks) + " ";
#else
  (void)ranks;
  return "";
#endif
}

// Why the MPI cases cannot run here, or "" when they can: lgh-bench built with MPI, and the launcher
// able to start two processes on this machine (a container without a resolvable host name cannot).
std::string mpiUnavailable() {
#ifdef LGH_MPIEXEC
  static const std::string why = [] {
    const fs::path log = fs::temp_directory_path() / ("lgh_mpiexec_probe_" + std::to_string(::getpid()) + ".txt");
    const Process p = run(mpiexec(2) + "true", log);
    fs::remove(log);
    return p.exitCode == 0 ? std::string() : "`" + mpiexec(2) + "true` fails here: " + p.output;
  }();
  return why;
#else
  return "lgh-bench is built without MPI (libmpich-dev not found by CMake)";
#endif
}

#define REQUIRE_MPI() \
  if (const std::string why = mpiUnavailable(); !why.empty()) GTEST_SKIP() << why

// The Cornell box at 96 x 54 with ~1K VPLs: 24 tiles of 16 px, a second or two to compute.
std::string referenceCommand(const fs::path& cache, const std::string& extra = "") {
  return std::string(LGH_BENCH_EXE) + " reference --scene " + (sourceDir() / "data/cornell_box.gltf").string() +
         " --width 96 --height 54 --vpls 1000 --tile 16 --threads 1 --cache-dir " + cache.string() + " " + extra;
}
constexpr int kTiles = 6 * 4;

// The one reference file a run left in `cache` (and no tile folder).
reference::ReferenceImage cachedReference(const fs::path& cache, std::string* key = nullptr) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(cache)) {
    EXPECT_EQ(entry.path().filename().string().rfind("tiles-", 0), std::string::npos)
        << entry.path() << ": tiles left after the reference was stored";
    if (entry.path().extension() == ".bin") files.push_back(entry.path());
  }
  EXPECT_EQ(files.size(), 1u);
  if (files.empty()) return {};
  auto image = reference::readReferenceFile(files[0], key);
  EXPECT_TRUE(image) << files[0];
  return image ? *image : reference::ReferenceImage{};
}

void expectSameReference(const reference::ReferenceImage& a, const reference::ReferenceImage& b) {
  ASSERT_FALSE(a.pixels.empty());
  EXPECT_TRUE(a.full()) << a.pixels.size() << " of " << a.width * a.height << " pixels";  // every pixel, once
  EXPECT_EQ(a.shadowed.size(), a.pixels.size());
  EXPECT_GT(a.rays, 0u);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(a.unshadowed, b.unshadowed);  // bit for bit
  EXPECT_EQ(a.shadowed, b.shadowed);
  EXPECT_EQ(a.rays, b.rays);
  EXPECT_EQ(a.pairs, b.pairs);
}

// "N computed (R of them again ...), C from the cache"
struct Counts {
  int computed = -1, redone = -1, cached = -1;
};
Counts counts(const std::string& output) {
  std::smatch m;
  Counts c;
  if (std::regex_search(output, m, std::regex(R"((\d+) computed \((\d+) of them again[^)]*\), (\d+) from the cache)")))
    c = {std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3])};
  return c;
}

// The tile files in a cache's tile folders.
std::vector<fs::path> tilePaths(const fs::path& cache) {
  std::vector<fs::path> paths;
  for (const auto& entry : fs::recursive_directory_iterator(cache))
    if (entry.path().filename().string().rfind("tile-", 0) == 0 && entry.path().extension() == ".bin")
      paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  return paths;
}

// One uninterrupted single-process reference, computed once for the suite.
const reference::ReferenceImage& oneProcessReference() {
  static TempDir dir;
  static const reference::ReferenceImage image = [] {
    const Process r = run(referenceCommand(dir.path() / "cache", "--out " + (dir.path() / "one.exr").string()),
                          dir.path() / "log.txt");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const Counts c = counts(r.output);
    EXPECT_EQ(c.computed, kTiles) << r.output;
    return cachedReference(dir.path() / "cache");
  }();
  return image;
}

TEST(ReferenceRuns, TwoRanksGiveTheOneProcessReference) {
  REQUIRE_MPI();
  TempDir dir;
  const Process r =
      run(mpiexec(2) + referenceCommand(dir.path() / "cache", "--out " + (dir.path() / "two.exr").string()),
          dir.path() / "log.txt");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("2 ranks x 1 threads"), std::string::npos) << r.output;
  EXPECT_EQ(counts(r.output).computed, kTiles) << r.output;
  expectSameReference(cachedReference(dir.path() / "cache"), oneProcessReference());
}

// Kills the run (SIGKILL, by the test hook) once `ranks` processes have each stored `after` tiles, then
// corrupts `corrupt` of the tiles left and truncates `truncate`; the restarted run must compute exactly
// the tiles without a whole file and give the uninterrupted reference.
void killAndResume(int ranks, int after, int corrupt, int truncate) {
  TempDir dir;
  const fs::path cache = dir.path() / "cache";
  const Process killed = run(mpiexec(ranks) + referenceCommand(cache, "--kill-after-tiles " + std::to_string(after)),
                             dir.path() / "killed.txt");
  ASSERT_NE(killed.exitCode, 0) << killed.output;
  const std::vector<fs::path> tiles = tilePaths(cache);
  ASSERT_GE(int(tiles.size()), after) << killed.output;  // each rank stored `after` before it died (others may not)
  ASSERT_LT(int(tiles.size()), kTiles);
  for (int i = 0; i < corrupt; ++i) {  // one bit flipped in the middle of the sums
    std::fstream io(tiles[size_t(i)], std::ios::in | std::ios::out | std::ios::binary);
    const std::streamoff middle = std::streamoff(fs::file_size(tiles[size_t(i)]) / 2);
    io.seekg(middle);
    const char c = char(io.get());
    io.seekp(middle);
    io.put(char(c ^ 0x04));
  }
  for (int i = corrupt; i < corrupt + truncate; ++i)
    fs::resize_file(tiles[size_t(i)], fs::file_size(tiles[size_t(i)]) / 3);
  const int whole = int(tiles.size()) - corrupt - truncate;

  const Process resumed = run(mpiexec(ranks) + referenceCommand(cache), dir.path() / "resumed.txt");
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  const Counts c = counts(resumed.output);
  EXPECT_EQ(c.cached, whole) << resumed.output;
  EXPECT_EQ(c.computed, kTiles - whole) << resumed.output;
  EXPECT_EQ(c.redone, corrupt + truncate) << resumed.output;
  expectSameReference(cachedReference(cache), oneProcessReference());
}

TEST(ReferenceRuns, KilledRunComputesOnlyTheMissingTiles) { killAndResume(1, 7, 0, 0); }
TEST(ReferenceRuns, CorruptAndTruncatedTilesAreComputedAgain) { killAndResume(1, 9, 2, 1); }
TEST(ReferenceRuns, KilledRanksResumeWithOnlyTheMissingTiles) {
  REQUIRE_MPI();
  killAndResume(2, 4, 1, 0);
}

TEST(ReferenceRuns, FailingTileEndsTheRunNamingIt) {
  TempDir dir;
  const Process r = run(referenceCommand(dir.path() / "cache", "--fail-tile 5"), dir.path() / "log.txt");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("tile 5 (x 80-95, y 0-15) failed"), std::string::npos) << r.output;
}

TEST(ReferenceRuns, FailingRankEndsEveryRankNamingTheRankAndTile) {
  REQUIRE_MPI();
  TempDir dir;
  // Tile 3 is dealt to rank 1 of 2 (missing tiles i -> rank i mod 2); rank 0 must not wait for it forever.
  const Process r = run(mpiexec(2) + referenceCommand(dir.path() / "cache", "--fail-tile 3"), dir.path() / "log.txt");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("rank 1 of 2: reference: tile 3 (x 48-63, y 0-15) failed"), std::string::npos) << r.output;
}

// A CSV line's cells ("a, b" quoted is one cell).
std::vector<std::string> csvCells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      cells.emplace_back();
    else
      cells.back() += c;
  }
  return cells;
}

// A CSV of lgh-bench (sweep, motion) without its timing columns (wall times and the machine's load).
std::vector<std::vector<std::string>> untimedCsv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> timed;
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> cells = csvCells(line);
    if (timed.empty())
      for (const std::string& name : cells)
        timed.push_back(name == "ms" || name.find("_ms") != std::string::npos || name == "others_cpu");
    std::vector<std::string> kept;
    for (size_t i = 0; i < cells.size(); ++i)
      if (i >= timed.size() || !timed[i]) kept.push_back(cells[i]);
    rows.push_back(kept);
  }
  return rows;
}

TEST(ReferenceRuns, SweepOnTwoRanksWritesTheOneProcessCsv) {
  REQUIRE_MPI();
  TempDir dir;
  const std::string sweep = std::string(LGH_BENCH_EXE) + " sweep --preset smoke --retries 0 --scene " +
                            (sourceDir() / "data/cornell_box.gltf").string() + " --threads 1";
  const Process one =
      run(sweep + " --out " + (dir.path() / "one").string() + " --cache-dir " + (dir.path() / "cache1").string(),
          dir.path() / "one.txt");
  ASSERT_EQ(one.exitCode, 0) << one.output;
  const Process two = run(mpiexec(2) + sweep + " --out " + (dir.path() / "two").string() + " --cache-dir " +
                              (dir.path() / "cache2").string(),
                          dir.path() / "two.txt");
  ASSERT_EQ(two.exitCode, 0) << two.output;
  const auto a = untimedCsv(dir.path() / "one/sweep.csv"), b = untimedCsv(dir.path() / "two/sweep.csv");
  ASSERT_GT(a.size(), 5u);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "row " << i;
  // The ranks shared the reference: one file each, the same.
  expectSameReference(cachedReference(dir.path() / "cache2"), cachedReference(dir.path() / "cache1"));
}

// lgh-bench motion on two ranks: rank 0 renders the sequence, both compute each frame's reference (6 tiles
// a frame, 3 each, rank 1 from its own copy of the moving scene), and the errors are the one process's.
TEST(ReferenceRuns, MotionOnTwoRanksWritesTheOneProcessCsv) {
  REQUIRE_MPI();
  TempDir dir;
  const std::string motion = std::string(LGH_BENCH_EXE) +
                             " motion --frames 3 --fps 4 --width 96 --height 54 --vpls 1000 --lightcut-samples 0"
                             " --reference-pixels 1";
  const Process one = run(
      motion + " --reference-cache " + (dir.path() / "cache1").string() + " --csv " + (dir.path() / "one.csv").string(),
      dir.path() / "one.txt");
  ASSERT_EQ(one.exitCode, 0) << one.output;
  const Process two = run(mpiexec(2) + motion + " --reference-cache " + (dir.path() / "cache2").string() + " --csv " +
                              (dir.path() / "two.csv").string(),
                          dir.path() / "two.txt");
  ASSERT_EQ(two.exitCode, 0) << two.output;
  EXPECT_NE(two.output.find("2 ranks (the references shared)"), std::string::npos) << two.output;
  const auto a = untimedCsv(dir.path() / "one.csv"), b = untimedCsv(dir.path() / "two.csv");
  ASSERT_EQ(a.size(), 1u + 3u * 4u);  // the header, 3 frames of 4 configurations
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "row " << i;
}

}  // namespace
}  // namespace lgh::test
