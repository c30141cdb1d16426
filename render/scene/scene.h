#pragma once
// A glTF scene flattened for rendering: every triangle in scene space (node transforms applied) in one
// vertex stream, grouped by material; materials, decoded textures, punctual lights and cameras in
// scene space. Scene space is world space shifted by Scene::origin (chosen at load time, in double
// precision: the centre of the geometry snapped to a power-of-two grid about the scene's size, so a
// scene near the world origin keeps origin 0), so every float coordinate the renderer sees is about
// the size of the scene wherever the file placed it: a model 1e6 units from the world origin keeps
// the precision it has at the origin. Loading validates everything the renderer relies on and fails with
// SceneLoadError ("<file>: <problem>") rather than handing on bad data.

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/scene/animation.h"

namespace lgh {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool empty() const { return min.x > max.x; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return empty() ? glm::vec3(0) : max - min; }
  float diagonal() const { return glm::length(extent()); }
};

struct Texture {
  std::string name;  // image name or URI, for messages
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // 8-bit RGBA, rows top-down as stored in the file; colour data is sRGB-encoded
};

// glTF alphaMode. BLEND is rendered opaque (a deferred renderer has one surface per pixel); the
// loader warns when a scene uses it.
enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};  // linear
  int baseColorTexture = -1;        // index into Scene::textures, -1 if none
  glm::vec3 emission{0.0f};         // emissiveFactor * KHR_materials_emissive_strength (linear radiance scale)
  int emissiveTexture = -1;         // index into Scene::textures, -1 if none
  // Which TEXCOORD_n set each texture reads, and its KHR_texture_transform (uv' = (M * (u, v, 1)).xy;
  // identity without the extension).
  int baseColorTexCoord = 0, emissiveTexCoord = 0;
  glm::mat3 baseColorUvTransform{1.0f}, emissiveUvTransform{1.0f};
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // MASK: a surface point with alpha < alphaCutoff is not there (camera, rays, VPLs)
  bool doubleSided = false;  // false: back faces are culled for the camera (glTF); rays see both sides
  bool isEmissive() const { return emission.r > 0 || emission.g > 0 || emission.b > 0; }
};

enum class LightType { Point, Spot, Directional };

struct PunctualLight {  // KHR_lights_punctual, in scene space
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};       // point, spot
  glm::vec3 direction{0, 0, -1};  // spot, directional: unit direction the light travels (node's -Z)
  glm::vec3 intensity{1.0f};      // color * intensity: candela (W/sr) for point/spot, lux (W/m^2) for directional
  float range = 0.0f;             // 0 = infinite
  float innerConeCos = 1.0f, outerConeCos = 0.70710678f;  // spot only: cos of the cone angles
};

struct Camera {
  std::string name;
  glm::vec3 position{0.0f};
  glm::mat3 orientation{1.0f};          // columns: right, up, back (camera looks along -column 2), orthonormal
  float yfov = 0.7853982f;              // radians
  float aspectRatio = 0.0f;             // as stored in the file; 0 = unspecified (the image's aspect is used)
  float znear = 0.01f, zfar = 1000.0f;  // a file's camera without zfar gets FLT_MAX: an infinite projection
};

struct MaterialRange {  // triangles [firstTriangle, firstTriangle + triangleCount) use `material`
  std::uint32_t material = 0, firstTriangle = 0, triangleCount = 0;
};

struct Scene {
  std::filesystem::path source;
  glm::dvec3 origin{0.0};                        // world position of scene space's origin: world = origin + p
  std::vector<glm::vec3> positions;              // scene space (see origin)
  std::vector<glm::vec3> normals;                // unit; generated (flat) where the file has none
  std::vector<glm::vec2> texcoords;              // TEXCOORD_0, (0,0) where the file has none
  std::vector<glm::vec2> texcoords1;             // TEXCOORD_1, (0,0) where the file has none
  std::vector<glm::vec4> colors;                 // COLOR_0 (linear RGBA), white where the file has none
  std::vector<std::uint32_t> indices;            // 3 per triangle, triangles grouped by material (see materialRanges)
  std::vector<std::uint32_t> triangleMaterials;  // one per triangle
  std::vector<MaterialRange> materialRanges;
  std::vector<Material> materials;  // at least one (a default grey material if the file has none)
  std::vector<Texture> textures;
  std::vector<PunctualLight> lights;
  std::vector<Camera> cameras;
  SceneAnimation animation;           // what moves, and how (empty for a still scene): see poseScene
  Bounds bounds;                      // of all triangle vertices, scene space, wherever the animation moves them
  std::vector<std::string> warnings;  // recoverable problems (missing texture, skipped point primitives, ...)

  size_t triangleCount() const { return indices.size() / 3; }
  // The camera named `name`; throws SceneLoadError listing the available names if there is none.
  const Camera& camera(const std::string& name) const;
};

struct SceneLoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Loads .gltf or .glb. Throws SceneLoadError("<path>: <problem>") for anything the renderer cannot use.
Scene loadScene(const std::filesystem::path& path);

// A camera that frames `bounds` (looking down -Z from in front of the box, slightly above its centre).
Camera frameBounds(const Bounds& bounds, float aspectRatio);

}  // namespace lgh
