#include "render/gl/memory.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <map>
#include <utility>

#include "render/gl/gl.h"

namespace lgh::gl {

std::string formatBytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB"};
  int unit = 0;
  while (bytes >= 1000.0 && unit < 4) {
    bytes /= 1000.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof(text), unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
  return text;
}

size_t MemoryRegistry::ownerBytes(const std::string& owner) const {
  size_t bytes = 0;
  for (const auto& [id, object] : objects_)
    if (object.label.owner == owner) bytes += object.bytes;
  return bytes;
}

std::vector<MemoryRegistry::Owner> MemoryRegistry::byOwner() const {
  std::map<std::string, Owner> owners;
  for (const auto& [id, object] : objects_) {
    Owner& o = owners[object.label.owner];
    o.owner = object.label.owner;
    o.bytes += object.bytes;
    ++o.objects;
  }
  std::vector<Owner> list;
  for (auto& [name, owner] : owners) list.push_back(owner);
  std::stable_sort(list.begin(), list.end(), [](const Owner& a, const Owner& b) { return a.bytes > b.bytes; });
  return list;
}

std::vector<MemoryRegistry::Object> MemoryRegistry::objects() const {
  std::vector<Object> list;
  for (const auto& [id, object] : objects_) list.push_back(object);
  return list;
}

void MemoryRegistry::check(const Label& label, size_t bytes) const {
  const std::string what = label.text() + " needs " + formatBytes(double(bytes)) + label.sizeNote();
  if (limit_ > 0 && live_ + bytes > limit_)
    throw OutOfMemory("GPU memory: " + what + ", but " + formatBytes(double(live_)) + " of the limit of " +
                      formatBytes(double(limit_)) + " (gpu-memory-limit) are in use");
  const size_t free = deviceFreeBytes();
  if (free > 0 && bytes > free)
    throw OutOfMemory("GPU memory: " + what + ", but the device reports " + formatBytes(double(free)) + " free");
}

std::uint64_t MemoryRegistry::add(Label label, size_t bytes) {
  check(label, bytes);
  const std::uint64_t id = nextId_++;
  objects_.emplace_back(id, Object{std::move(label), bytes});
  live_ += bytes;
  peak_ = std::max(peak_, live_);
  return id;
}

void MemoryRegistry::remove(std::uint64_t id) {
  // Objects die mostly in reverse order of their making: search from the back.
  for (auto it = objects_.rbegin(); it != objects_.rend(); ++it)
    if (it->first == id) {
      live_ -= it->second.bytes;
      objects_.erase(std::next(it).base());
      return;
    }
}

MemoryRegistry& memory() {
  static MemoryRegistry registry;
  return registry;
}

size_t deviceFreeBytes() {
  GLint kilobytes[4] = {0, 0, 0, 0};
  if (GLAD_GL_NVX_gpu_memory_info)
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, kilobytes);
  else if (GLAD_GL_ATI_meminfo)
    glGetIntegerv(GL_VBO_FREE_MEMORY_ATI, kilobytes);  // [0]: the pool's free kilobytes
  else
    return 0;
  return size_t(std::max(kilobytes[0], 0)) * 1024;
}

Allocation::Allocation(Label label, size_t bytes) : id_(memory().add(std::move(label), bytes)) {}

Allocation::~Allocation() {
  if (id_) memory().remove(id_);
}

Allocation::Allocation(Allocation&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

Allocation& Allocation::operator=(Allocation&& other) noexcept {
  if (this != &other) {
    if (id_) memory().remove(id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

}  // namespace lgh::gl
