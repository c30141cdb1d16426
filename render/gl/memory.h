#pragma once
// GPU memory, accounted where it is allocated. Every gl::Buffer and gl::Texture2D carries a Label (its
// owner, a pass or the scene, and its name there) and records its bytes in one registry while it lives,
// so what the frame holds is summed from the objects themselves, never tallied by hand in the passes.
// The label also names the object for the driver (glObjectLabel), so debuggers show it.
//
// Before storage is made the registry checks it against a budget: the device's reported free memory
// (GL_NVX_gpu_memory_info, GL_ATI_meminfo, where the driver has one) and the limit a user sets. A request
// past it throws gl::OutOfMemory naming the object, the settings its size follows and the bytes, rather
// than leaving a GL_OUT_OF_MEMORY (or a crash) for later.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lgh::gl {

struct Label {
  Label() = default;
  Label(std::string owner, std::string name, std::string scaledBy = {})
      : owner(std::move(owner)), name(std::move(name)), scaledBy(std::move(scaledBy)) {}
  std::string owner;     // who holds it: a pass (the names of FrameStats::passes), "scene", ...
  std::string name;      // what it is in its owner
  std::string scaledBy;  // the settings its size follows, for error messages ("" when fixed)
  std::string text() const { return owner + ": " + name; }
  // " (its size follows ...)" for error messages, or nothing for a fixed size.
  std::string sizeNote() const { return scaledBy.empty() ? "" : " (its size follows " + scaledBy + ")"; }
};

struct OutOfMemory : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "12.3 MB" (decimal units, as the tables print them).
std::string formatBytes(double bytes);

class MemoryRegistry {
 public:
  struct Object {
    Label label;
    size_t bytes = 0;
  };
  struct Owner {
    std::string owner;
    size_t bytes = 0, objects = 0;
  };

  size_t liveBytes() const { return live_; }
  size_t peakBytes() const { return peak_; }
  void resetPeak() { peak_ = live_; }  // the peak from now on
  size_t ownerBytes(const std::string& owner) const;
  std::vector<Owner> byOwner() const;  // largest first
  std::vector<Object> objects() const;

  // The most bytes the GL objects may hold together (0: no limit of the user's). The device's own
  // reported free memory is checked besides.
  void setLimit(size_t bytes) { limit_ = bytes; }
  size_t limit() const { return limit_; }

 private:
  friend class Allocation;
  std::uint64_t add(Label label, size_t bytes);
  void remove(std::uint64_t id);
  void check(const Label& label, size_t bytes) const;

  std::vector<std::pair<std::uint64_t, Object>> objects_;  // live, in allocation order
  std::uint64_t nextId_ = 1;
  size_t live_ = 0, peak_ = 0, limit_ = 0;
};

// The process's registry: the objects of every context (the engine renders on one thread).
MemoryRegistry& memory();

// Free device memory the driver reports, in bytes, or 0 where it reports none (llvmpipe, most drivers
// without GL_NVX_gpu_memory_info or GL_ATI_meminfo).
size_t deviceFreeBytes();

// One live object's entry in memory(), held by the object: added on construction (after the budget
// check, which throws gl::OutOfMemory), removed on destruction. Move-only, like the GL handle beside it.
class Allocation {
 public:
  Allocation() = default;
  Allocation(Label label, size_t bytes);
  ~Allocation();
  Allocation(Allocation&& other) noexcept;
  Allocation& operator=(Allocation&& other) noexcept;
  Allocation(const Allocation&) = delete;
  Allocation& operator=(const Allocation&) = delete;

 private:
  std::uint64_t id_ = 0;
};

}  // namespace lgh::gl
