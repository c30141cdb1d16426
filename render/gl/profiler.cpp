#include "render/gl/profiler.h"

namespace lgh::gl {
namespace {
QueryHandle timestampNow() {
  GLuint q = 0;
  glCreateQueries(GL_TIMESTAMP, 1, &q);
  glQueryCounter(q, GL_TIMESTAMP);
  return QueryHandle(q);
}
}  // namespace

Profiler::Scope::Scope(Profiler& profiler, const char* name) : profiler_(profiler), index_(profiler.pending_.size()) {
  glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
  if (profiler_.synchronous_) glFinish();
  profiler_.pending_.push_back({name, timestampNow(), QueryHandle(), 0.0});
  start_ = std::chrono::steady_clock::now();
}

Profiler::Scope::~Scope() {
  Pending& p = profiler_.pending_[index_];
  p.end = timestampNow();
  if (profiler_.synchronous_) {
    glFinish();
    p.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }
  glPopDebugGroup();
}

std::vector<PassTiming> Profiler::collect() {
  std::vector<PassTiming> timings;
  for (Pending& p : pending_) {
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(p.begin.id(), GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(p.end.id(), GL_QUERY_RESULT, &t1);
    timings.push_back({p.name, t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0, p.wallMs});
  }
  pending_.clear();
  return timings;
}

void Profiler::reset() { pending_.clear(); }

}  // namespace lgh::gl
