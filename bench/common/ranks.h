#pragma once
// The processes of one lgh-bench run: MPI_COMM_WORLD when lgh-bench is built with MPI (Debian's MPICH,
// found by CMake: LGH_HAVE_MPI) and started by mpiexec / srun, else one process of rank 0. Only what
// the benchmarks need: who am I, broadcast and gather bytes from rank 0, agree that every rank is done,
// and end every rank at once when one fails (MPI_Abort), so that a failure never leaves the others
// waiting in a collective call.

#include <string>
#include <vector>

namespace lgh::bench {

class Ranks {
 public:
  // MPI_Init (when built with MPI); once per process, in main, before anything else.
  Ranks(int& argc, char**& argv);
  ~Ranks();  // MPI_Finalize
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  // The ranks of this run (set up by the constructor); one rank 0 of 1 without MPI.
  static const Ranks& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }
  int ranksOnThisHost() const { return hostSize_; }  // for the default thread count
  std::string name() const;                          // "rank 1 of 4"

  // Rank 0's bytes on every rank.
  void broadcast(std::string& bytes) const;
  // Every rank's bytes, on rank 0 in rank order (empty elsewhere).
  std::vector<std::string> gather(const std::string& bytes) const;
  void barrier() const;
  // Ends every rank of the run with `code` after printing `message` (prefixed by this rank's name
  // when distributed) on stderr. Without MPI: exits this process.
  [[noreturn]] void abort(const std::string& message, int code = 1) const;

 private:
  Ranks() = default;
  int rank_ = 0, size_ = 1, hostSize_ = 1;
  bool initialized_ = false;
};

}  // namespace lgh::bench
