// loadScene: glTF 2.0 (.gltf / .glb) → a flat, validated, world-space Scene.
//
// tinygltf parses the JSON and loads the buffers (compiled in tinygltf_impl.cpp without its image
// code); everything after that is ours: every index the file contains is range-checked and every
// byte an accessor reads is bounds-checked, because tinygltf 2.7 checks neither and a bad file must
// end in SceneLoadError, never a crash. Order of work:
//   read file → parse (tinygltf) → asset version, required extensions (gltf_container) → node world
//   transforms (tree check, double precision: gltf_nodes) → meshes (accessors decoded by gltf_accessors;
//   triangles bucketed by material, world positions in double) → scene origin (positions shifted to
//   scene space, then float) → materials (+ the textures they use: gltf_materials) → lights →
//   cameras → group triangles by material, bounds.
// This file assembles the scene; the helpers report problems as gltf::FileProblem without the path,
// and loadScene turns them into SceneLoadError("<path>: <problem>").
// Strictness: what the glTF 2.0 specification forbids and would change the image (the Khronos
// validator's errors that apply to what this renderer reads; docs/gltf.md, "Strict glTF 2.0") ends in
// SceneLoadError. Numbers are checked where they become float: a JSON value such as 1e39 is a
// finite double but an infinite float.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <limits>
#include <string>
#include <vector>

#include "render/scene/gltf_accessors.h"
#include "render/scene/gltf_animation.h"
#include "render/scene/gltf_checks.h"
#include "render/scene/gltf_container.h"
#include "render/scene/gltf_materials.h"
#include "render/scene/gltf_nodes.h"
#include "render/scene/scene.h"

namespace lgh {

const Camera& Scene::camera(const std::string& name) const {
  for (const Camera& c : cameras)
    if (c.name == name) return c;
  std::string available;
  for (const Camera& c : cameras) available += (available.empty() ? "'" : ", '") + c.name + "'";
  throw SceneLoadError(source.string() + ": no camera named '" + name + "'; " +
                       (cameras.empty() ? std::string("the scene has no cameras") : "available cameras: " + available));
}

namespace gltf {
namespace {

namespace fs = std::filesystem;

// Unit normal of triangle (a, b, c) wound counter-clockwise, or `fallback` for zero-area (or
// non-finite) triangles. Computed in double: slivers far from the origin lose their normal in float.
glm::vec3 faceNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::vec3& fallback) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  if (!(length > 0.0) || !std::isfinite(length)) return fallback;
  return glm::vec3(n / length);
}

class GltfLoader {
 public:
  explicit GltfLoader(const fs::path& path) : path_(path) { scene_.source = path; }

  Scene load() {
    model_ = parseFile(path_, readFile(path_), scene_.warnings);
    checkAssetVersion(model_);
    meshQuantization_ = extensionUsed(model_, "KHR_mesh_quantization");
    checkRequiredExtensions(model_);
    nodes_ = displayedNodes(model_);
    scene_.animation = readAnimations(model_, scene_.warnings);
    loadMeshes();
    loadMaterials(model_, path_, trianglesByMaterial_, defaultMaterial_ >= 0, blendMaterials_, scene_);
    loadLights();
    loadCameras();
    groupTrianglesByMaterial();
    boundAnimation();
    missingNormals_.flush(scene_.warnings);
    blendMaterials_.flush(scene_.warnings);
    badNormals_.flush(scene_.warnings);
    skippedPrimitives_.flush(scene_.warnings);
    return std::move(scene_);
  }

 private:
  std::string nodeLabel(size_t i) const { return gltf::nodeLabel(model_, i); }

  // ---------------------------------------------------------------------------------------------
  // Meshes

  // Index into scene_.materials for a primitive's material (-1: the glTF default material).
  std::uint32_t materialSlot(int material, const std::string& what) {
    if (material >= 0) {
      if (size_t(material) >= model_.materials.size())
        fail(what + " uses material " + std::to_string(material) + ", but the file has " +
             std::to_string(model_.materials.size()) + " materials");
      return std::uint32_t(material);
    }
    if (defaultMaterial_ < 0) defaultMaterial_ = int(model_.materials.size());
    return std::uint32_t(defaultMaterial_);
  }

  void loadMeshes() {
    for (int nodeIndex : nodes_.drawOrder) {
      const tinygltf::Node& node = model_.nodes[nodeIndex];
      if (node.mesh < 0) continue;
      if (size_t(node.mesh) >= model_.meshes.size())
        fail(nodeLabel(nodeIndex) + " references mesh " + std::to_string(node.mesh) + ", but the file has " +
             std::to_string(model_.meshes.size()) + " meshes");
      const tinygltf::Mesh& mesh = model_.meshes[node.mesh];
      for (size_t p = 0; p < mesh.primitives.size(); ++p)
        appendPrimitive(mesh.primitives[p],
                        label("mesh", size_t(node.mesh), mesh.name) + " primitive " + std::to_string(p), nodeIndex);
    }
    if (triangleCount_ == 0) {
      size_t primitives = 0;
      for (const auto& m : model_.meshes) primitives += m.primitives.size();
      fail("the scene contains no triangles to render (" + std::to_string(model_.meshes.size()) + " meshes, " +
           std::to_string(primitives) + " primitives, " + std::to_string(nodes_.drawOrder.size()) +
           " nodes in the scene)");
    }
    chooseSceneOrigin();
  }

  // The primitive's triangles as corner indices (its indices, or 0..n-1, triangulated from strips and fans).
  std::vector<std::uint32_t> primitiveTriangles(const tinygltf::Primitive& prim, const std::string& what,
                                                size_t vertexCount) {
    std::vector<std::uint32_t> indices;
    if (prim.indices >= 0) {
      indices = readIndices(model_, prim.indices, what + " indices");
      for (size_t k = 0; k < indices.size(); ++k)
        if (indices[k] >= vertexCount)
          fail(what + ": index " + std::to_string(indices[k]) + " (entry " + std::to_string(k) +
               ") is out of range: the primitive has " + std::to_string(vertexCount) + " vertices");
    } else {
      indices.resize(vertexCount);
      for (size_t v = 0; v < vertexCount; ++v) indices[v] = std::uint32_t(v);
    }
    if (prim.mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0)
      skippedPrimitives_.add(what + " (trailing indices)");
    return triangulate(prim.mode, indices);
  }

  // A texture whose TEXCOORD set the primitive lacks would sample one texel everywhere
  // (validator: MESH_PRIMITIVE_TOO_FEW_TEXCOORDS).
  void checkTexCoordSets(const tinygltf::Primitive& prim, const std::string& what,
                         const std::vector<glm::vec2> (&texcoords)[2]) {
    if (prim.material < 0) return;
    const tinygltf::Material& m = model_.materials[size_t(prim.material)];
    const std::pair<const tinygltf::TextureInfo*, const char*> slots[] = {
        {&m.pbrMetallicRoughness.baseColorTexture, "base colour"}, {&m.emissiveTexture, "emissive"}};
    for (const auto& [info, slot] : slots) {
      const int set = effectiveTexCoord(*info);
      if (info->index < 0 || set < 0 || set > 1) continue;  // sets >= 2 are ignored with a warning later
      if (texcoords[set].empty())
        fail(what + ": its material " + label("material", size_t(prim.material), m.name) + " has a " + slot +
             " texture that reads TEXCOORD_" + std::to_string(set) + ", which the primitive does not have");
    }
  }

  // Appends the triangles' vertices (world positions, normals, texture coordinates, colours) to the
  // scene and their indices to `bucket` (the material's triangle list).
  void emitTriangles(const std::vector<std::uint32_t>& tris, const std::vector<glm::dvec3>& worldPositions,
                     const std::vector<glm::vec3>& normals, const glm::mat3& normalMatrix,
                     const std::vector<glm::vec2> (&texcoords)[2], const std::vector<glm::vec4>& colors,
                     std::vector<std::uint32_t>& bucket, const std::string& what,
                     std::vector<std::uint32_t>* emittedFrom) {
    const auto emitVertex = [&](std::uint32_t v, const glm::vec3& n) {
      if (emittedFrom) emittedFrom->push_back(v);
      worldPositions_.push_back(worldPositions[v]);
      scene_.normals.push_back(n);
      scene_.texcoords.push_back(texcoords[0].empty() ? glm::vec2(0.0f) : texcoords[0][v]);
      scene_.texcoords1.push_back(texcoords[1].empty() ? glm::vec2(0.0f) : texcoords[1][v]);
      scene_.colors.push_back(colors.empty() ? glm::vec4(1.0f) : colors[v]);
    };
    const glm::vec3 up(0.0f, 1.0f, 0.0f);  // normal of zero-area triangles: any unit vector, never NaN
    if (normals.empty()) {
      // Flat shading needs one vertex per corner: the same position gets a different normal in
      // each triangle it belongs to.
      for (size_t t = 0; t < tris.size(); t += 3) {
        const glm::vec3 n =
            faceNormal(worldPositions[tris[t]], worldPositions[tris[t + 1]], worldPositions[tris[t + 2]], up);
        for (int c = 0; c < 3; ++c) {
          bucket.push_back(std::uint32_t(worldPositions_.size()));
          emitVertex(tris[t + c], n);
        }
      }
    } else {
      // Emit each used vertex once (primitives often index a small part of a shared accessor).
      std::vector<std::uint32_t> remap(worldPositions.size(), std::numeric_limits<std::uint32_t>::max());
      for (size_t t = 0; t < tris.size(); t += 3) {
        for (int c = 0; c < 3; ++c) {
          const std::uint32_t v = tris[t + c];
          if (remap[v] == std::numeric_limits<std::uint32_t>::max()) {
            remap[v] = std::uint32_t(worldPositions_.size());
            glm::vec3 n = normalMatrix * normals[v];
            const float length = glm::length(n);
            if (length > 0.0f && std::isfinite(length)) {
              n /= length;
            } else {  // zero normal in the file: use the face's
              badNormals_.add(what);
              n = faceNormal(worldPositions[tris[t]], worldPositions[tris[t + 1]], worldPositions[tris[t + 2]], up);
            }
            emitVertex(v, n);
          }
          bucket.push_back(remap[v]);
        }
      }
    }
  }

  // Transforms one primitive to world space (double) and appends its vertices (only those its
  // triangles use) and triangles (to its material's bucket). A primitive under a moving node also keeps
  // its vertices in mesh space, for poseScene.
  void appendPrimitive(const tinygltf::Primitive& prim, const std::string& what, int nodeIndex) {
    const glm::dmat4& world = nodes_.world[size_t(nodeIndex)];
    if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
      skippedPrimitives_.add(what);
      return;
    }
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        prim.mode != TINYGLTF_MODE_TRIANGLE_FAN)
      fail(what + " has unknown primitive mode " + std::to_string(prim.mode));
    const auto attribute = [&](const char* name) {
      const auto it = prim.attributes.find(name);
      return it == prim.attributes.end() ? -1 : it->second;
    };
    const int positionAccessor = attribute("POSITION");
    if (positionAccessor < 0) fail(what + " has no POSITION attribute");

    const std::vector<glm::vec3> positions =
        readAttribute<3>(model_, positionAccessor, "POSITION", what, size_t(-1), meshQuantization_);
    const size_t vertexCount = positions.size();

    std::vector<std::uint32_t> tris = primitiveTriangles(prim, what, vertexCount);
    const std::uint32_t material = materialSlot(prim.material, what);
    if (tris.empty()) return;

    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texcoords[2];
    std::vector<glm::vec4> colors;
    if (const int a = attribute("NORMAL"); a >= 0)
      normals = readAttribute<3>(model_, a, "NORMAL", what, vertexCount, meshQuantization_);
    else
      missingNormals_.add(what);
    if (const int a = attribute("TEXCOORD_0"); a >= 0)
      texcoords[0] = readAttribute<2>(model_, a, "TEXCOORD_0", what, vertexCount, meshQuantization_);
    if (const int a = attribute("TEXCOORD_1"); a >= 0)
      texcoords[1] = readAttribute<2>(model_, a, "TEXCOORD_1", what, vertexCount, meshQuantization_);
    if (const int a = attribute("COLOR_0"); a >= 0)
      colors = readColors(model_, a, what, vertexCount, meshQuantization_);
    checkTexCoordSets(prim, what, texcoords);

    // A mirroring transform turns counter-clockwise triangles clockwise: swap two corners so the
    // front face (and the flat normal) stay on the side glTF meant.
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    if (mirrored)
      for (size_t t = 0; t < tris.size(); t += 3) std::swap(tris[t + 1], tris[t + 2]);
    // Normals transform by the inverse transpose (non-uniform scale), then are renormalised.
    const glm::mat3 normalMatrix(glm::inverseTranspose(glm::dmat3(world)));

    // World positions stay in double until the scene origin is known (loadMeshes): a scene far from
    // the origin keeps its vertices' relative precision.
    std::vector<glm::dvec3> worldPositions(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v) {
      worldPositions[v] = glm::dvec3(world * glm::dvec4(glm::dvec3(positions[v]), 1.0));
      for (int c = 0; c < 3; ++c)
        if (!fitsFloat(worldPositions[v][c]))
          fail(what + ": POSITION of vertex " + std::to_string(v) +
               " is not finite (NaN or Inf) after the node transform, or beyond float range");
    }

    const bool moves = scene_.animation.moves(nodeIndex);
    std::vector<std::uint32_t> emittedFrom;
    MovingPrimitive moving;
    moving.node = nodeIndex;
    moving.firstVertex = std::uint32_t(worldPositions_.size());
    emitTriangles(tris, worldPositions, normals, normalMatrix, texcoords, colors, trianglesFor(material), what,
                  moves ? &emittedFrom : nullptr);
    triangleCount_ += tris.size() / 3;
    if (moves) {
      moving.vertexCount = std::uint32_t(emittedFrom.size());
      for (std::uint32_t v : emittedFrom) {
        moving.positions.push_back(positions[v]);
        if (!normals.empty()) moving.normals.push_back(normals[v]);
      }
      scene_.animation.primitives.push_back(std::move(moving));
    }
  }

  // Scene space: world space shifted by an origin near the geometry, computed in double. Every later
  // float (vertices, lights, cameras, the BVH, VPLs, the hierarchy, G-buffer positions) is then
  // relative to the scene, so its precision does not depend on where the file put the scene. The
  // origin is the centre of the bounds snapped to a grid of g = the next power of two above the
  // bounds' diagonal: a scene near the world origin (|centre| < g / 2, most files) keeps origin 0 and
  // its world coordinates, and scene-space coordinates never exceed about 1.4 g anywhere.
  void chooseSceneOrigin() {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec3& p : worldPositions_) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    scene_.origin = glm::dvec3(0.0);
    if (!worldPositions_.empty()) {
      const double grid = std::exp2(std::ceil(std::log2(std::max(glm::length(hi - lo), 1e-30))));
      scene_.origin = glm::round(0.5 * (lo + hi) / grid) * grid;
    }
    scene_.positions.resize(worldPositions_.size());
    for (size_t i = 0; i < worldPositions_.size(); ++i)
      scene_.positions[i] = glm::vec3(worldPositions_[i] - scene_.origin);
    worldPositions_.clear();
    worldPositions_.shrink_to_fit();
  }

  std::vector<std::uint32_t>& trianglesFor(std::uint32_t material) {
    if (trianglesByMaterial_.size() <= material) trianglesByMaterial_.resize(material + 1);
    return trianglesByMaterial_[material];
  }

  // ---------------------------------------------------------------------------------------------
  // Lights and cameras

  // Fails unless the node's position fits a float in world space.
  void checkPosition(int node) const {
    const glm::dvec3 world(nodes_.world[size_t(node)][3]);
    for (int c = 0; c < 3; ++c)
      if (!fitsFloat(world[c])) fail(nodeLabel(size_t(node)) + " has a position beyond float range");
  }

  void loadLights() {
    for (int nodeIndex : nodes_.drawOrder) {
      const tinygltf::Node& node = model_.nodes[nodeIndex];
      const auto ext = node.extensions.find("KHR_lights_punctual");
      if (ext == node.extensions.end()) continue;
      const tinygltf::Value& value = ext->second;
      if (!value.IsObject() || !value.Has("light") || !value.Get("light").IsNumber())
        fail(nodeLabel(nodeIndex) + " has a KHR_lights_punctual extension without a light index");
      const double index = value.Get("light").GetNumberAsDouble();
      if (!(index >= 0.0) || index >= double(model_.lights.size()) || index != std::floor(index))
        fail(nodeLabel(nodeIndex) + " references light " + std::to_string(value.Get("light").GetNumberAsInt()) +
             ", but the file defines " + std::to_string(model_.lights.size()) + " KHR_lights_punctual lights");
      scene_.lights.push_back(makeLight(size_t(index), nodeIndex));
      scene_.animation.lightNodes.push_back(nodeIndex);
    }
  }

  PunctualLight makeLight(size_t index, int nodeIndex) const {
    const tinygltf::Light& src = model_.lights[index];
    const std::string what = label("light", index, src.name);
    PunctualLight light;
    light.name = !src.name.empty()                       ? src.name
                 : !model_.nodes[nodeIndex].name.empty() ? model_.nodes[nodeIndex].name
                                                         : what;
    if (src.type == "point")
      light.type = LightType::Point;
    else if (src.type == "spot")
      light.type = LightType::Spot;
    else if (src.type == "directional")
      light.type = LightType::Directional;
    else
      fail(what + " has unknown type '" + src.type + "' (expected point, spot or directional)");
    glm::vec3 color(1.0f);  // glTF default: white
    if (src.color.size() == 3)
      color = glm::vec3(src.color[0], src.color[1], src.color[2]);
    else if (!src.color.empty())
      fail(what + " has a color that is not 3 numbers");
    if (!finite(color) || glm::any(glm::lessThan(color, glm::vec3(0.0f))) || !(src.intensity >= 0.0) ||
        !fitsFloat(src.intensity) || !finite(color * float(src.intensity)))
      fail(what + " has a negative or non-finite color or intensity");
    light.intensity = color * float(src.intensity);
    // tinygltf stores an absent range as 0; a range given in the file must be > 0 (and a float).
    if (src.range != 0.0 && (!(src.range > 0.0) || !fitsFloat(src.range)))
      fail(what + " has range " + number(src.range) + " (must be a finite number > 0, or absent for infinite)");
    light.range = float(src.range);
    checkPosition(nodeIndex);
    // Lights shine down their node's -Z.
    if (!lightPlacement(nodes_.world[size_t(nodeIndex)], scene_.origin, light.position, light.direction))
      fail(nodeLabel(size_t(nodeIndex)) + " has a degenerate transform (zero scale)");
    if (light.type == LightType::Spot) {
      const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
      const double halfPi = 1.5707963267948966;
      if (!(outer > 0.0 && outer <= halfPi + 1e-6) || !(inner >= 0.0 && inner <= outer))
        fail(what + ": spot cone angles must satisfy 0 <= innerConeAngle <= outerConeAngle <= pi/2 (got " +
             std::to_string(inner) + ", " + std::to_string(outer) + ")");
      light.innerConeCos = float(std::cos(inner));
      light.outerConeCos = float(std::cos(std::min(outer, halfPi)));
    }
    return light;
  }

  void loadCameras() {
    std::vector<char> used(model_.cameras.size(), 0);
    for (int nodeIndex : nodes_.drawOrder) {
      const tinygltf::Node& node = model_.nodes[nodeIndex];
      if (node.camera < 0) continue;
      if (size_t(node.camera) >= model_.cameras.size())
        fail(nodeLabel(nodeIndex) + " references camera " + std::to_string(node.camera) + ", but the file has " +
             std::to_string(model_.cameras.size()) + " cameras");
      used[node.camera] = 1;
      const tinygltf::Camera& src = model_.cameras[node.camera];
      const std::string what = label("camera", size_t(node.camera), src.name);
      if (src.type == "orthographic") {
        scene_.warnings.push_back(what + " is orthographic; only perspective cameras are supported, so it is skipped");
        continue;
      }
      if (src.type != "perspective") fail(what + " has unknown type '" + src.type + "'");
      const auto& p = src.perspective;
      if (!(p.yfov > 0.0 && p.yfov < 3.14159))
        fail(what + " has yfov " + std::to_string(p.yfov) + ", expected 0 < yfov < pi");
      if (!(p.znear > 0.0) || !fitsFloat(p.znear))
        fail(what + " has znear " + number(p.znear) + " (must be a finite number > 0)");
      // zfar 0 is tinygltf's "absent" (an infinite projection); a given zfar must exceed znear.
      if (p.zfar != 0.0 && (!(p.zfar > p.znear) || !fitsFloat(p.zfar)))
        fail(what + " has zfar " + number(p.zfar) + " not greater than znear " + number(p.znear));
      if (p.aspectRatio != 0.0 && (!(p.aspectRatio > 0.0) || !fitsFloat(p.aspectRatio)))
        fail(what + " has aspectRatio " + number(p.aspectRatio) + " (must be a finite number > 0)");
      Camera camera;
      camera.name = !src.name.empty() ? src.name : !node.name.empty() ? node.name : what;
      checkPosition(nodeIndex);
      if (!cameraPlacement(nodes_.world[size_t(nodeIndex)], scene_.origin, camera.position, camera.orientation))
        fail(what + ": its node transform is degenerate");
      camera.yfov = float(p.yfov);
      camera.aspectRatio = p.aspectRatio > 0.0 ? float(p.aspectRatio) : 0.0f;
      camera.znear = float(p.znear);
      // Absent zfar: infinite. Reversed Z keeps depth precision for any far plane, so a huge one stands in.
      camera.zfar = p.zfar > 0.0 ? float(p.zfar) : std::numeric_limits<float>::max();
      scene_.cameras.push_back(camera);
      scene_.animation.cameraNodes.push_back(nodeIndex);
    }
    for (size_t i = 0; i < used.size(); ++i)
      if (!used[i])
        scene_.warnings.push_back(label("camera", i, model_.cameras[i].name) +
                                  " is attached to no node of the scene; skipped");
  }

  // ---------------------------------------------------------------------------------------------
  // Final layout

  // Concatenates the per-material buckets in material order (each keeps file order inside), so
  // every material's triangles are one contiguous range the renderer can draw or sample at once.
  void groupTrianglesByMaterial() {
    scene_.indices.reserve(3 * triangleCount_);
    scene_.triangleMaterials.reserve(triangleCount_);
    for (size_t m = 0; m < trianglesByMaterial_.size(); ++m) {
      const std::vector<std::uint32_t>& bucket = trianglesByMaterial_[m];
      if (bucket.empty()) continue;
      MaterialRange range;
      range.material = std::uint32_t(m);
      range.firstTriangle = std::uint32_t(scene_.indices.size() / 3);
      range.triangleCount = std::uint32_t(bucket.size() / 3);
      scene_.materialRanges.push_back(range);
      scene_.indices.insert(scene_.indices.end(), bucket.begin(), bucket.end());
      scene_.triangleMaterials.insert(scene_.triangleMaterials.end(), range.triangleCount, range.material);
    }
    trianglesByMaterial_.clear();
    // Every stored vertex belongs to a triangle (vertices are emitted on first use).
    for (const glm::vec3& p : scene_.positions) scene_.bounds.extend(p);
  }

  // The bounds cover the whole animation, so that what is scaled to them (the clamp distance, a sun's
  // emitting disk) holds still while things move: the moving vertices at every key time and at 64 times
  // between the first and the last.
  void boundAnimation() {
    if (scene_.animation.empty() || scene_.animation.primitives.empty()) return;
    const SceneAnimation& a = scene_.animation;
    std::vector<double> times;
    for (const AnimationChannel& c : a.channels) times.insert(times.end(), c.times.begin(), c.times.end());
    for (int i = 0; i <= 64; ++i) times.push_back(a.start + (a.end - a.start) * i / 64.0);
    Scene posed;  // the moving part only: the scene stays as the file places it until the caller poses it
    posed.origin = scene_.origin;
    posed.animation = a;
    posed.positions = scene_.positions;
    posed.normals = scene_.normals;
    for (double t : times) {
      poseScene(posed, t);
      for (const MovingPrimitive& p : a.primitives)
        for (std::uint32_t v = 0; v < p.vertexCount; ++v) scene_.bounds.extend(posed.positions[p.firstVertex + v]);
    }
  }

  fs::path path_;
  tinygltf::Model model_;
  Scene scene_;
  SceneNodes nodes_;
  std::vector<glm::dvec3> worldPositions_;  // vertices in world space until chooseSceneOrigin()
  bool meshQuantization_ = false;           // KHR_mesh_quantization used: more attribute formats allowed
  std::vector<std::vector<std::uint32_t>> trianglesByMaterial_;
  size_t triangleCount_ = 0;
  int defaultMaterial_ = -1;  // slot of the added default material, -1 if none is needed yet
  WarningGroup missingNormals_{"primitives without NORMAL: flat face normals generated"};
  WarningGroup badNormals_{"zero or non-finite vertex normals replaced by face normals"};
  WarningGroup blendMaterials_{"alphaMode BLEND is rendered opaque (one surface per pixel in a deferred renderer)"};
  WarningGroup skippedPrimitives_{"point/line primitives (or trailing indices of triangle lists) skipped"};
};

}  // namespace
}  // namespace gltf

Scene loadScene(const std::filesystem::path& path) {
  try {
    return gltf::GltfLoader(path).load();
  } catch (const gltf::FileProblem& problem) {
    throw SceneLoadError(path.string() + ": " + problem.what());
  } catch (const SceneLoadError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw SceneLoadError(path.string() + ": out of memory while loading (implausibly large counts in the file?)");
  } catch (const std::exception& e) {  // nothing else may escape: the contract is SceneLoadError
    throw SceneLoadError(path.string() + ": " + e.what());
  }
}

}  // namespace lgh
