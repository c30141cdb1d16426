#pragma once
// GL error reporting. With a debug context, KHR_debug messages of type ERROR are recorded by a
// synchronous callback (never thrown from inside the driver) and raised as gl::Error at the next
// checkErrors(); without one, checkErrors() still polls glGetError().

#include <stdexcept>
#include <string>

namespace lgh::gl {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void installDebugOutput();
// Throws gl::Error("<where>: <messages>") if the driver reported an error since the last check.
void checkErrors(const char* where);

// RAII debug group: names a pass in captures (RenderDoc, apitrace) and in error messages.
class DebugGroup {
 public:
  explicit DebugGroup(const char* name);
  ~DebugGroup();
  DebugGroup(const DebugGroup&) = delete;
  DebugGroup& operator=(const DebugGroup&) = delete;
};

}  // namespace lgh::gl
