#pragma once
// Per-pass timings. Each pass runs inside a Profiler::Scope, which opens a KHR_debug group and records
// GPU timestamps around it; with `synchronous` the scope also calls glFinish on both sides and records
// wall time, which is the trustworthy number on a software rasterizer (llvmpipe defers work, so its
// timestamps are taken when commands are queued, not when they run).

#include <chrono>
#include <string>
#include <vector>

#include "render/gl/resource.h"

namespace lgh::gl {

struct PassTiming {
  std::string name;
  double gpuMs = 0;   // from GL_TIMESTAMP queries
  double wallMs = 0;  // glFinish-bracketed wall time (synchronous mode), else 0
};

class Profiler {
 public:
  explicit Profiler(bool synchronous = true) : synchronous_(synchronous) {}
  void setSynchronous(bool synchronous) { synchronous_ = synchronous; }
  bool synchronous() const { return synchronous_; }

  class Scope {
   public:
    Scope(Profiler& profiler, const char* name);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    Profiler& profiler_;
    size_t index_;
    std::chrono::steady_clock::time_point start_;
  };

  // Resolves the queries of the frame (waits for them) and returns one entry per scope, in order.
  std::vector<PassTiming> collect();
  void reset();

 private:
  struct Pending {
    std::string name;
    QueryHandle begin, end;
    double wallMs = 0;
  };
  bool synchronous_;
  std::vector<Pending> pending_;
};

}  // namespace lgh::gl
