#pragma once
// The scene on the GPU: vertex streams for rasterization (drawn per material, since core GL cannot
// index samplers per triangle), material and punctual-light SSBOs, textures, and the BVH for compute
// shaders. Built once per scene; passes only bind it. Two things may change afterwards, each with a
// version that whatever is derived from it watches: the punctual lights (the viewer moves them, an
// animation carries them: lightsVersion(), which the VPL emitter table, S0 and the hierarchy and the
// direct pass's light list follow) and, in an animated scene, the vertices (follow(): geometryVersion(),
// with the BVH rebuilt, which the emissive-triangle table and S0 follow).

#include <vector>

#include "render/gl/buffer.h"
#include "render/gl/texture.h"
#include "render/scene/bvh.h"
#include "render/scene/gpu_bvh.h"
#include "render/scene/scene.h"
#include "shared/scene_types.h"

namespace lgh {

// The BVH's quality when meshes move and it is built every frame: Medium builds Sponza's compressed 8-wide
// BVH in 51 ms against High's 325, for 1.2x the nodes and 1.3x the triangle tests a shadow ray; Low
// (Morton codes) took 73 ms for 1.6x the nodes (docs/measurements.md, "The BVH under motion").
inline constexpr BvhQuality kFollowBvhQuality = BvhQuality::Medium;

class SceneGpu {
 public:
  // The BVH in `layout`: what the tracing passes compile their traversal for (TracingProgram).
  // The BVH is built at `quality`; rebuilds when meshes move (follow) at kFollowBvhQuality.
  explicit SceneGpu(const Scene& scene, BvhLayout layout = BvhLayout::Compressed8,
                    BvhQuality quality = BvhQuality::High);

  // Binds the BVH (at its LGH_TEXTURE_BVH_* units), scene triangles, materials, textures and punctual
  // lights (at their LGH_BINDING_* slots) for compute shaders.
  void bindForCompute() const;
  // Issues one draw per material range; `onMaterial` binds that material's textures and uniforms.
  template <typename OnMaterial>
  void drawByMaterial(OnMaterial&& onMaterial) const {
    glBindVertexArray(vertexArray_.id());
    for (const MaterialRange& range : scene_.materialRanges) {
      onMaterial(range.material, materials_[range.material]);
      glDrawElements(GL_TRIANGLES, GLsizei(range.triangleCount * 3), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(size_t(range.firstTriangle) * 3 * sizeof(std::uint32_t)));
    }
    glBindVertexArray(0);
  }
  // The GL texture for a scene texture index, or a 1x1 white texture for -1.
  const gl::Texture2D& texture(int index) const;

  const Scene& scene() const { return scene_; }
  const Bvh& bvh() const { return bvh_; }
  const std::vector<gpu::GpuPunctualLight>& punctualLights() const { return lights_; }
  const std::vector<gpu::GpuMaterial>& materials() const { return materials_; }
  // The punctual lights as loaded, or as last set; the same order as punctualLights().
  const std::vector<PunctualLight>& lights() const { return sceneLights_; }
  // Replaces light `index` (throws std::out_of_range) and re-uploads the light buffer.
  void setPunctualLight(size_t index, const PunctualLight& light);
  unsigned lightsVersion() const { return lightsVersion_; }
  // Takes what poseScene moved in the Scene this was made from: the lights' records (one version step for
  // them all) and the vertices, re-uploaded with the BVH built anew over them.
  void follow(const PoseChange& change);
  unsigned geometryVersion() const { return geometryVersion_; }
  double bvhBuildMs() const { return bvhBuildMs_; }  // of the last build (at construction, or the last follow)

 private:
  void buildBvh(BvhLayout layout, BvhQuality quality);
  void uploadLight(size_t index, const PunctualLight& light);

  const Scene& scene_;
  Bvh bvh_;
  double bvhBuildMs_ = 0;
  std::vector<gpu::GpuMaterial> materials_;
  std::vector<PunctualLight> sceneLights_;
  std::vector<gpu::GpuPunctualLight> lights_;
  unsigned lightsVersion_ = 0, geometryVersion_ = 0;
  gl::Buffer positions_, normals_, texcoords_, texcoords1_, colors_, indices_;
  gl::VertexArrayHandle vertexArray_;
  GpuBvh gpuBvh_;
  gl::Buffer materialBuffer_, lightBuffer_;
  gl::Buffer sceneTriangles_, sceneVertices_, textureInfos_, texels_;  // for compute shaders at ray hits
  std::vector<gl::Texture2D> textures_;
  gl::Texture2D white_;
};

}  // namespace lgh
