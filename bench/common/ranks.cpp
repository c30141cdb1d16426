#include "bench/common/ranks.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#ifdef LGH_HAVE_MPI
#include <mpi.h>
#endif

namespace lgh::bench {
namespace {

const Ranks* theWorld = nullptr;

#ifdef LGH_HAVE_MPI
// Waits for a non-blocking collective, sleeping between tests: MPICH's blocking calls poll at 100% of a
// core, which a rank waiting for another on the same host would take from the ranks still working (and
// from their timed frames).
void wait(MPI_Request& request) {
  // MPICH advances a collective only inside MPI calls: test continuously for a while (a large message
  // moves in steps), then every 2 ms.
  const auto start = std::chrono::steady_clock::now();
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    if (std::chrono::steady_clock::now() - start > std::chrono::milliseconds(100))
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

// Byte counts travel as int: a message is kept below 2 GiB (references are a few MB per case).
int byteCount(size_t size) {
  if (size > size_t(1) << 30) throw std::runtime_error("MPI message of " + std::to_string(size) + " bytes (> 1 GiB)");
  return int(size);
}
#endif

}  // namespace

Ranks::Ranks(int& argc, char**& argv) {
#ifdef LGH_HAVE_MPI
  // Funneled: only the main thread calls MPI; the reference's Embree workers never do.
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  initialized_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm host;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  MPI_Comm_size(host, &hostSize_);
  MPI_Comm_free(&host);
#else
  (void)argc, (void)argv;
#endif
  theWorld = this;
}

Ranks::~Ranks() {
#ifdef LGH_HAVE_MPI
  // Ranks done before rank 0 wait here asleep (MPI_Finalize may synchronise at 100% of a core).
  if (initialized_ && distributed()) barrier();
  if (initialized_) MPI_Finalize();
#endif
  if (theWorld == this) theWorld = nullptr;
}

const Ranks& Ranks::world() {
  static const Ranks single;  // before main's (or without one): rank 0 of 1
  return theWorld ? *theWorld : single;
}

std::string Ranks::name() const { return "rank " + std::to_string(rank_) + " of " + std::to_string(size_); }

void Ranks::broadcast(std::string& bytes) const {
#ifdef LGH_HAVE_MPI
  if (!distributed()) return;
  unsigned long long size = bytes.size();
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD, &request);
  wait(request);
  bytes.resize(size_t(size));
  MPI_Ibcast(bytes.data(), byteCount(bytes.size()), MPI_BYTE, 0, MPI_COMM_WORLD, &request);
  wait(request);
#else
  (void)bytes;
#endif
}

std::vector<std::string> Ranks::gather(const std::string& bytes) const {
  std::vector<std::string> all;
  if (!distributed()) {
    all.push_back(bytes);
    return all;
  }
#ifdef LGH_HAVE_MPI
  int size = byteCount(bytes.size());
  std::vector<int> sizes(root() ? size_t(size_) : 0), offsets;
  MPI_Request request;
  MPI_Igather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait(request);
  std::string joined;
  if (root()) {
    size_t total = 0;
    for (int s : sizes) offsets.push_back(byteCount(total)), total += size_t(s);
    joined.resize(total);
  }
  MPI_Igatherv(bytes.data(), size, MPI_BYTE, joined.data(), sizes.data(), offsets.data(), MPI_BYTE, 0, MPI_COMM_WORLD,
               &request);
  wait(request);
  for (size_t r = 0; r < sizes.size(); ++r) all.push_back(joined.substr(size_t(offsets[r]), size_t(sizes[r])));
#endif
  return all;
}

void Ranks::barrier() const {
#ifdef LGH_HAVE_MPI
  if (!distributed()) return;
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  wait(request);
#endif
}

void Ranks::abort(const std::string& message, int code) const {
  if (distributed())
    std::fprintf(stderr, "%s: %s\n", name().c_str(), message.c_str());
  else
    std::fprintf(stderr, "%s\n", message.c_str());
  std::fflush(stderr);
#ifdef LGH_HAVE_MPI
  if (distributed()) {
    // MPICH's launcher forwards a rank's stderr through a pipe to its proxy, and MPI_Abort may end the
    // proxy before it has read that pipe: the message, the one line saying what failed, would be lost
    // (it was, once in CI). Give the proxy a moment to forward it; only a failing run pays for it.
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    MPI_Abort(MPI_COMM_WORLD, code);
  }
#endif
  std::exit(code);
}

}  // namespace lgh::bench
