#pragma once
// The exact reference the sweep measures against (docs/design.md §7), independent of the GL code path: for a
// G-buffer read back from the renderer (positions, normals) and the renderer's input lights S0, every
// pixel sums every light's contribution (lgh/shading.h, double precision, the renderer's clamp
// distance) with its true visibility, traced with Embree on the CPU (std::thread workers,
// rtcOccluded16). The unshadowed sum comes out of the same loop.
//
// Shadow rays are the ones the GL passes trace (glsl/shadow_rays.comp, brute_force.comp with
// LGH_SHADOWED): from offsetRayOrigin(p, n) (glsl/shared/ray_offset.h, the same header) towards the
// light, ending 0.1% short of it, in float. The result is irradiance, before albedo: compare it with
// the renderer's Aov::Irradiance (unshadowed) and Aov::Irradiance x Aov::Visibility (shadowed).
//
// For large light counts a random subset of the pixels may be computed (each pixel kept with a given
// probability, independently of its content, so error statistics over the subset estimate the
// image's without bias). References are cached on disk under a key that names everything they
// depend on (loadReference / storeReference).
//
// This library links Embree and lgh (the shading model) only: no GL.

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lgh/light.h"

struct RTCDeviceTy;
struct RTCSceneTy;

namespace lgh::reference {

// Scene triangles in Embree, for occlusion (any-hit) queries. Thread-safe after construction.
class OcclusionScene {
 public:
  // positions: world-space vertices; indices: 3 per triangle. Throws std::runtime_error on an Embree
  // error (the message says which).
  OcclusionScene(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices);
  ~OcclusionScene();
  OcclusionScene(const OcclusionScene&) = delete;
  OcclusionScene& operator=(const OcclusionScene&) = delete;

  struct Ray {
    glm::vec3 origin;
    float tMin;
    glm::vec3 direction;
    float tMax;
  };
  // For each ray, 1 if any triangle is hit with tMin <= t <= tMax, else 0 (`threads` workers; 0: one
  // per hardware thread).
  std::vector<std::uint8_t> occluded(const std::vector<Ray>& rays, unsigned threads = 0) const;
  // One ray, on the calling thread (rtcOccluded1).
  bool occluded(const Ray& ray) const;

  RTCSceneTy* handle() const { return scene_; }
  // A hash of the triangles (vertex positions and indices): the occluders, for cache keys.
  std::uint64_t contentHash() const { return contentHash_; }

 private:
  std::uint64_t contentHash_ = 0;
  RTCDeviceTy* device_ = nullptr;
  RTCSceneTy* scene_ = nullptr;
};

// The shadow ray of the GL passes from the surface (p, n) to a light at q: origin offsetRayOrigin(p, n),
// unit direction, tMax 0.1% short of the light. Returns false (and no ray) when q is at the origin.
bool shadowRay(const glm::vec3& p, const glm::vec3& n, const glm::vec3& q, OcclusionScene::Ray& ray);

// What the reference is computed from.
struct ReferenceInput {
  int width = 0, height = 0;
  std::vector<glm::vec4> position;  // per pixel, rows top-down: xyz world position, w > 0 on geometry
  std::vector<glm::vec4> normal;    // per pixel: xyz unit shading normal
  std::vector<Light> lights;        // S0 as the GPU holds it (fromGpuLights: decoded normals)
  double clampDistance = 0;         // d_c (Renderer::clampDistance())
};

struct ReferenceOptions {
  bool shadowed = true;      // also the shadowed sum (one ray per pixel and lit light)
  double pixelFraction = 1;  // < 1: each pixel computed with this probability (a random subset)
  std::uint32_t subsetSeed = 1;
  unsigned threads = 0;  // 0: one per hardware thread
  bool progress = true;  // progress bar with the time left, on stderr
  std::string label = "reference";
};

// Irradiance (W/m^2, before albedo) at the computed pixels.
struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;   // computed pixels, y * width + x with rows top-down, ascending
  std::vector<glm::dvec3> unshadowed;  // exact sum over every light, per computed pixel
  std::vector<glm::dvec3> shadowed;    // the same with each light's visibility (empty if not computed)
  // How it was made (kept through the cache):
  double seconds = 0;       // wall time of the computation
  std::uint64_t pairs = 0;  // pixel-light pairs evaluated
  std::uint64_t rays = 0;   // shadow rays traced
  unsigned threads = 0;
  std::size_t lightCount = 0;
  bool full() const { return pixels.size() == size_t(width) * size_t(height); }
};

// The pixel subset: every pixel for fraction >= 1; else pixel i with probability `fraction`,
// decided by a hash of (i, seed). Ascending indices.
std::vector<std::uint32_t> choosePixels(int width, int height, double fraction, std::uint32_t seed);

// Throws std::invalid_argument on inconsistent input (sizes, a non-positive clamp distance is allowed).
ReferenceImage computeReference(const OcclusionScene& scene, const ReferenceInput& input,
                                const ReferenceOptions& options);
// The same sums at the given pixels only (ascending indices y * width + x; the subset options are
// not used): a tile of a reference computed in parts (bench/reference/reference_tiles.h). Each pixel's sums
// depend on that pixel alone, so the parts of an image are its pixels, bit for bit.
ReferenceImage computePixels(const OcclusionScene& scene, const ReferenceInput& input,
                             std::vector<std::uint32_t> pixels, const ReferenceOptions& options);

// --- Cache. A reference is stored under a description of everything it depends on (the caller writes
// it: scene path and modification time, camera, resolution, light settings and seed, clamp, pixel
// subset, content hashes); the file name is a hash of the description, and the description is stored
// in the file and compared on load, so a collision can never hand back the wrong reference.
std::string cacheFileName(const std::string& description);
std::optional<ReferenceImage> loadReference(const std::filesystem::path& dir, const std::string& description);
// A cache file read whatever its description (stored in *description): for tools and tests.
std::optional<ReferenceImage> readReferenceFile(const std::filesystem::path& path, std::string* description = nullptr);
// Written to a temporary file and renamed into place. Throws std::runtime_error on a write failure.
void storeReference(const std::filesystem::path& dir, const std::string& description, const ReferenceImage& image);

// 64-bit FNV-1a over bytes, for cache keys.
std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t seed = 0xcbf29ce484222325ull);
// Independent of the lights' order (a sum of per-light hashes), so a light set built by atomics in a
// different order keys the same reference.
std::uint64_t hashLights(const std::vector<Light>& lights);
std::string hex64(std::uint64_t value);

}  // namespace lgh::reference
