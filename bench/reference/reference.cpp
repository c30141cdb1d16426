#include "bench/reference/reference.h"

#include <embree3/rtcore.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <thread>

#include "bench/common/progress.h"
#include "lgh/shading.h"
#include "shared/ray_offset.h"

namespace lgh::reference {
namespace {

unsigned workerCount(unsigned requested) {
  return requested > 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
}

void throwOnEmbreeError(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error == RTC_ERROR_NONE) return;
  static const char* const names[] = {"none",          "unknown",         "invalid argument", "invalid operation",
                                      "out of memory", "unsupported CPU", "cancelled"};
  const char* name = unsigned(error) < sizeof names / sizeof names[0] ? names[error] : "unknown";
  throw std::runtime_error(std::string("Embree: ") + what + " failed: " + name);
}

// Runs work(item) for items [0, count) on `threads` workers, handing out `grain` items at a time;
// tick() is called on the calling thread about every 100 ms with the number of items finished.
template <typename Work, typename Tick>
void parallelFor(size_t count, size_t grain, unsigned threads, Work&& work, Tick&& tick) {
  std::atomic<size_t> next{0}, finished{0};
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (;;) {
        const size_t first = next.fetch_add(grain);
        if (first >= count) break;
        const size_t last = std::min(count, first + grain);
        for (size_t i = first; i < last; ++i) work(i);
        finished.fetch_add(last - first);
      }
    });
  while (finished.load() < count) {
    tick(finished.load());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& t : pool) t.join();
  tick(count);
}

// splitmix64: the pixel subset's coin flips.
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// S0 in the forms the inner loop wants: double for shading, float for the rays (as the GPU).
struct LightArrays {
  std::vector<glm::dvec3> position, intensity, normal;
  std::vector<double> omni;
  std::vector<glm::vec3> positionFloat;
  explicit LightArrays(const std::vector<Light>& lights) {
    for (const Light& l : lights) {
      position.emplace_back(l.position);
      intensity.emplace_back(l.intensity);
      normal.push_back(unitNormal(l));
      omni.push_back(omniFraction(l));
      positionFloat.push_back(l.position);
    }
  }
  size_t size() const { return position.size(); }
};

// Up to 16 shadow rays from one pixel, traced together.
struct RayPacket {
  RTCRay16 rays;
  glm::dvec3 contribution[16];
  int count = 0;
};

}  // namespace

OcclusionScene::OcclusionScene(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  if (indices.size() % 3 != 0) throw std::invalid_argument("OcclusionScene: index count is not a multiple of 3");
  for (std::uint32_t i : indices)
    if (i >= positions.size()) throw std::invalid_argument("OcclusionScene: index out of range");
  contentHash_ = hashBytes(indices.data(), indices.size() * sizeof(std::uint32_t),
                           hashBytes(positions.data(), positions.size() * sizeof(glm::vec3)));
  device_ = rtcNewDevice(nullptr);
  if (!device_)
    throw std::runtime_error("Embree: rtcNewDevice failed (error " + std::to_string(int(rtcGetDeviceError(nullptr))) +
                             ")");
  scene_ = rtcNewScene(device_);
  // Robust (watertight) traversal: a ray through a shared edge cannot slip between two triangles.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  if (!indices.empty()) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), positions.size()));
    auto* triangles = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), indices.size() / 3));
    throwOnEmbreeError(device_, "allocating geometry buffers");
    for (size_t i = 0; i < positions.size(); ++i) std::memcpy(vertices + 3 * i, &positions[i], 3 * sizeof(float));
    std::memcpy(triangles, indices.data(), indices.size() * sizeof(std::uint32_t));
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
  throwOnEmbreeError(device_, "building the scene");
}

OcclusionScene::~OcclusionScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool OcclusionScene::occluded(const Ray& r) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = r.origin.x, ray.org_y = r.origin.y, ray.org_z = r.origin.z, ray.tnear = r.tMin;
  ray.dir_x = r.direction.x, ray.dir_y = r.direction.y, ray.dir_z = r.direction.z, ray.tfar = r.tMax;
  ray.mask = 0xffffffffu;
  ray.flags = 0;
  ray.time = 0.0f;
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

std::vector<std::uint8_t> OcclusionScene::occluded(const std::vector<Ray>& rays, unsigned threads) const {
  std::vector<std::uint8_t> result(rays.size(), 0);
  parallelFor(
      rays.size(), 4096, workerCount(threads), [&](size_t i) { result[i] = occluded(rays[i]) ? 1 : 0; }, [](size_t) {});
  return result;
}

bool shadowRay(const glm::vec3& p, const glm::vec3& n, const glm::vec3& q, OcclusionScene::Ray& ray) {
  // As glsl/shadow_rays.comp: float throughout, so that both trace the same segment.
  const glm::vec3 origin = gpu::offsetRayOrigin(p, n);
  const glm::vec3 toLight = q - origin;
  const float d = glm::length(toLight);
  if (!(d > 0.0f)) return false;
  ray.origin = origin;
  ray.tMin = 0.0f;
  ray.direction = toLight / d;
  ray.tMax = d * (1.0f - 1e-3f);
  return true;
}

std::vector<std::uint32_t> choosePixels(int width, int height, double fraction, std::uint32_t seed) {
  const size_t count = size_t(std::max(width, 0)) * size_t(std::max(height, 0));
  std::vector<std::uint32_t> pixels;
  if (fraction >= 1.0) {
    pixels.resize(count);
    for (size_t i = 0; i < count; ++i) pixels[i] = std::uint32_t(i);
    return pixels;
  }
  const double threshold = std::max(fraction, 0.0) * 18446744073709551616.0;  // 2^64
  for (size_t i = 0; i < count; ++i)
    if (double(mix64(std::uint64_t(i) ^ (std::uint64_t(seed) << 32))) < threshold) pixels.push_back(std::uint32_t(i));
  return pixels;
}

ReferenceImage computeReference(const OcclusionScene& scene, const ReferenceInput& input,
                                const ReferenceOptions& options) {
  if (!(options.pixelFraction > 0.0)) throw std::invalid_argument("reference: the pixel fraction must be > 0");
  return computePixels(scene, input, choosePixels(input.width, input.height, options.pixelFraction, options.subsetSeed),
                       options);
}

ReferenceImage computePixels(const OcclusionScene& scene, const ReferenceInput& input,
                             std::vector<std::uint32_t> pixels, const ReferenceOptions& options) {
  const size_t pixelCount = size_t(std::max(input.width, 0)) * size_t(std::max(input.height, 0));
  if (input.width <= 0 || input.height <= 0) throw std::invalid_argument("reference: empty image");
  if (input.position.size() != pixelCount || input.normal.size() != pixelCount)
    throw std::invalid_argument("reference: the G-buffer does not have width x height pixels");
  if (!(input.clampDistance >= 0.0)) throw std::invalid_argument("reference: the clamp distance must be >= 0");
  for (size_t i = 0; i < pixels.size(); ++i)
    if (pixels[i] >= pixelCount || (i > 0 && pixels[i] <= pixels[i - 1]))
      throw std::invalid_argument("reference: the pixels must be ascending image indices");

  ReferenceImage out;
  out.width = input.width;
  out.height = input.height;
  out.pixels = std::move(pixels);
  out.unshadowed.assign(out.pixels.size(), glm::dvec3(0.0));
  if (options.shadowed) out.shadowed.assign(out.pixels.size(), glm::dvec3(0.0));
  out.threads = workerCount(options.threads);
  out.lightCount = input.lights.size();

  const LightArrays lights(input.lights);
  const double clamp = input.clampDistance;
  std::atomic<std::uint64_t> rays{0}, pairs{0};
  const auto start = std::chrono::steady_clock::now();
  bench::ProgressBar bar(options.label + " (" + std::to_string(out.pixels.size()) + " pixels x " +
                             std::to_string(lights.size()) + " lights, " + std::to_string(out.threads) + " threads)",
                         double(out.pixels.size()), options.progress);

  auto pixelWork = [&](size_t k) {
    const std::uint32_t index = out.pixels[k];
    const glm::vec4 p4 = input.position[index];
    if (!(p4.w > 0.0f)) return;  // background: no surface, nothing lit
    const glm::vec3 p(p4), n(input.normal[index]);
    const glm::dvec3 x(p), nx(n);
    const glm::vec3 origin = gpu::offsetRayOrigin(p, n);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    alignas(64) RayPacket packet;
    glm::dvec3 unshadowed(0.0), shadowed(0.0);
    std::uint64_t traced = 0;
    auto flush = [&] {
      if (packet.count == 0) return;
      alignas(64) int valid[16];
      for (int j = 0; j < 16; ++j) valid[j] = j < packet.count ? -1 : 0;
      rtcOccluded16(valid, scene.handle(), &context, &packet.rays);
      for (int j = 0; j < packet.count; ++j)
        if (packet.rays.tfar[j] != -std::numeric_limits<float>::infinity()) shadowed += packet.contribution[j];
      traced += std::uint64_t(packet.count);
      packet.count = 0;
    };
    for (size_t i = 0; i < lights.size(); ++i) {
      const glm::dvec3 e =
          lightContribution(lights.position[i], lights.intensity[i], lights.normal[i], lights.omni[i], x, &nx, clamp);
      if (e == glm::dvec3(0.0)) continue;  // as the GPU: unlit lights trace no ray
      unshadowed += e;
      if (!options.shadowed) continue;
      // The ray of glsl/brute_force.comp (LGH_SHADOWED) and shadow_rays.comp, in float.
      const glm::vec3 toLight = lights.positionFloat[i] - origin;
      const float d = glm::length(toLight);
      if (!(d > 0.0f)) {  // the light at the ray origin: nothing can be in between
        shadowed += e;
        continue;
      }
      const glm::vec3 direction = toLight / d;
      const int j = packet.count++;
      RTCRay16& r = packet.rays;
      r.org_x[j] = origin.x, r.org_y[j] = origin.y, r.org_z[j] = origin.z, r.tnear[j] = 0.0f;
      r.dir_x[j] = direction.x, r.dir_y[j] = direction.y, r.dir_z[j] = direction.z, r.tfar[j] = d * (1.0f - 1e-3f);
      r.time[j] = 0.0f, r.mask[j] = 0xffffffffu, r.id[j] = 0, r.flags[j] = 0;
      packet.contribution[j] = e;
      if (packet.count == 16) flush();
    }
    flush();
    out.unshadowed[k] = unshadowed;
    if (options.shadowed) out.shadowed[k] = shadowed;
    rays.fetch_add(traced, std::memory_order_relaxed);
    pairs.fetch_add(lights.size(), std::memory_order_relaxed);
  };
  parallelFor(out.pixels.size(), 4, out.threads, pixelWork, [&](size_t done) { bar.update(double(done)); });
  bar.finish();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.rays = rays.load();
  out.pairs = pairs.load();
  return out;
}

// --- Cache.

std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t seed) {
  std::uint64_t h = seed;
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

std::uint64_t hashLights(const std::vector<Light>& lights) {
  std::uint64_t sum = 0;
  for (const Light& l : lights) {
    const float values[9] = {l.position.x,  l.position.y, l.position.z, l.intensity.x, l.intensity.y,
                             l.intensity.z, l.normal.x,   l.normal.y,   l.normal.z};
    sum += mix64(hashBytes(values, sizeof values));
  }
  return sum ^ mix64(lights.size());
}

std::string hex64(std::uint64_t value) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(value));
  return buffer;
}

std::string cacheFileName(const std::string& description) {
  return "reference-" + hex64(hashBytes(description.data(), description.size())) + ".bin";
}

namespace {

constexpr char kMagic[8] = {'L', 'G', 'H', 'R', 'E', 'F', '0', '1'};

template <typename T>
void writePod(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}
template <typename T>
bool readPod(std::istream& in, T& value) {
  return bool(in.read(reinterpret_cast<char*>(&value), sizeof value));
}
template <typename T>
void writeVector(std::ostream& out, const std::vector<T>& values) {
  writePod(out, std::uint64_t(values.size()));
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(T)));
}
template <typename T>
bool readVector(std::istream& in, std::vector<T>& values, std::uint64_t limit) {
  std::uint64_t n = 0;
  if (!readPod(in, n) || n > limit) return false;
  values.resize(size_t(n));
  return bool(in.read(reinterpret_cast<char*>(values.data()), std::streamsize(n * sizeof(T))));
}

}  // namespace

std::optional<ReferenceImage> loadReference(const std::filesystem::path& dir, const std::string& description) {
  std::string stored;
  std::optional<ReferenceImage> image = readReferenceFile(dir / cacheFileName(description), &stored);
  if (!image || stored != description) return std::nullopt;
  return image;
}

std::optional<ReferenceImage> readReferenceFile(const std::filesystem::path& path, std::string* description) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  char magic[8];
  std::uint64_t length = 0;
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0 || !readPod(in, length) || length > (1u << 20))
    return std::nullopt;
  std::string stored(size_t(length), '\0');
  if (!in.read(stored.data(), std::streamsize(length))) return std::nullopt;
  if (description) *description = stored;
  ReferenceImage image;
  std::uint64_t lightCount = 0;
  if (!readPod(in, image.width) || !readPod(in, image.height) || !readPod(in, image.seconds) ||
      !readPod(in, image.pairs) || !readPod(in, image.rays) || !readPod(in, image.threads) || !readPod(in, lightCount))
    return std::nullopt;
  image.lightCount = size_t(lightCount);
  const std::uint64_t limit = std::uint64_t(std::max(image.width, 0)) * std::uint64_t(std::max(image.height, 0));
  if (!readVector(in, image.pixels, limit) || !readVector(in, image.unshadowed, limit) ||
      !readVector(in, image.shadowed, limit))
    return std::nullopt;
  if (image.unshadowed.size() != image.pixels.size() ||
      (!image.shadowed.empty() && image.shadowed.size() != image.pixels.size()))
    return std::nullopt;
  return image;
}

void storeReference(const std::filesystem::path& dir, const std::string& description, const ReferenceImage& image) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw std::runtime_error(dir.string() + ": cannot create the reference cache folder: " + error.message());
  const std::filesystem::path path = dir / cacheFileName(description);
  const std::filesystem::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(temporary.string() + ": cannot open for writing");
    out.write(kMagic, 8);
    writePod(out, std::uint64_t(description.size()));
    out.write(description.data(), std::streamsize(description.size()));
    writePod(out, image.width);
    writePod(out, image.height);
    writePod(out, image.seconds);
    writePod(out, image.pairs);
    writePod(out, image.rays);
    writePod(out, image.threads);
    writePod(out, std::uint64_t(image.lightCount));
    writeVector(out, image.pixels);
    writeVector(out, image.unshadowed);
    writeVector(out, image.shadowed);
    if (!out) throw std::runtime_error(temporary.string() + ": write failed");
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary);
    throw std::runtime_error(path.string() + ": cannot move the reference into place: " + error.message());
  }
}

}  // namespace lgh::reference
