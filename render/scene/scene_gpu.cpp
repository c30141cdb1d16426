#include "render/scene/scene_gpu.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {
namespace {

gpu::GpuPunctualLight toGpu(const PunctualLight& light) {
  gpu::GpuPunctualLight g{};
  g.position = light.position;
  g.type = light.type == LightType::Point  ? gpu::kLightPoint
           : light.type == LightType::Spot ? gpu::kLightSpot
                                           : gpu::kLightDirectional;
  g.direction = light.direction;
  g.range = light.range;
  g.intensity = light.intensity;
  g.innerConeCos = light.innerConeCos;
  g.outerConeCos = light.outerConeCos;
  return g;
}

gpu::GpuMaterial toGpu(const Material& m) {
  gpu::GpuMaterial g{};
  g.baseColorFactor = m.baseColorFactor;
  g.emission = m.emission;
  g.baseColorTexture = m.baseColorTexture;
  g.emissiveTexture = m.emissiveTexture;
  g.alphaCutoff = m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f;
  g.baseColorTexCoord = std::uint32_t(m.baseColorTexCoord);
  g.emissiveTexCoord = std::uint32_t(m.emissiveTexCoord);
  // Rows of the 2x3 affine part of the 3x3 uv transform (glm is column-major: M[column][row]).
  const auto row = [](const glm::mat3& t, int r) { return glm::vec4(t[0][r], t[1][r], t[2][r], 0.0f); };
  g.baseColorUvRow0 = row(m.baseColorUvTransform, 0);
  g.baseColorUvRow1 = row(m.baseColorUvTransform, 1);
  g.emissiveUvRow0 = row(m.emissiveUvTransform, 0);
  g.emissiveUvRow1 = row(m.emissiveUvTransform, 1);
  return g;
}

gl::Texture2D uploadTexture(const Texture& texture) {
  const int levels = 1 + int(std::floor(std::log2(float(std::max(texture.width, texture.height)))));
  // Colour textures are sRGB-encoded in glTF; the sampler decodes them to linear.
  gl::Texture2D t({passes::kScene, "texture " + texture.name}, texture.width, texture.height, GL_SRGB8_ALPHA8, levels);
  t.upload(GL_RGBA, GL_UNSIGNED_BYTE, texture.rgba.data());
  glGenerateTextureMipmap(t.id());
  t.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  t.setWrap(GL_REPEAT);
  return t;
}

// Every texture's texels in one buffer for compute shaders (no sampler arrays indexed per hit in core
// GL). Textures that would overflow the shader storage block limit are subsampled by 2 until they fit:
// they only colour VPLs, whose albedo needs no full resolution (the G-buffer samples the originals).
void packTexels(const Scene& scene, std::vector<gpu::GpuTextureInfo>& infos, std::vector<std::uint32_t>& texels) {
  const size_t maxTexels = gl::maxStorageBlockBytes() / sizeof(std::uint32_t);
  for (const Texture& t : scene.textures) {
    int step = 1;
    while (texels.size() + size_t(t.width / step) * size_t(t.height / step) > maxTexels && step < 1 << 12) step *= 2;
    const std::uint32_t w = std::uint32_t(std::max(1, t.width / step)), h = std::uint32_t(std::max(1, t.height / step));
    infos.push_back({std::uint32_t(texels.size()), w, h, 0});
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const std::uint8_t* p =
            &t.rgba[4 * (size_t(y * std::uint32_t(step)) * size_t(t.width) + x * std::uint32_t(step))];
        texels.push_back(std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                         std::uint32_t(p[3]) << 24);
      }
  }
}

}  // namespace

void SceneGpu::buildBvh(BvhLayout layout, BvhQuality quality) {
  const auto start = std::chrono::steady_clock::now();
  bvh_ = lgh::buildBvh(scene_.positions, scene_.indices, layout, quality);
  // Alpha-masked triangles are marked in the BVH so that traversal tests alpha only where it can matter.
  for (gpu::BvhTriangle& t : bvh_.triangles)
    if (scene_.materials[scene_.triangleMaterials[t.sceneTriangle]].alphaMode == AlphaMode::Mask) {
      t.flags |= gpu::kBvhTriangleAlphaMasked;
      bvh_.alphaMasked = true;
    }
  gpuBvh_ = GpuBvh(bvh_);
  bvhBuildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

SceneGpu::SceneGpu(const Scene& scene, BvhLayout layout, BvhQuality quality) : scene_(scene) {
  gl::DebugGroup group("upload scene");
  buildBvh(layout, quality);
  // An animated scene's vertices move (follow): their buffers take updates.
  const GLbitfield moving = scene.animation.primitives.empty() ? 0 : GL_DYNAMIC_STORAGE_BIT;
  positions_ = gl::Buffer::fromVector({passes::kScene, "vertex positions"}, scene.positions, moving);
  normals_ = gl::Buffer::fromVector({passes::kScene, "vertex normals"}, scene.normals, moving);
  texcoords_ = gl::Buffer::fromVector({passes::kScene, "texture coordinates 0"}, scene.texcoords, 0);
  texcoords1_ = gl::Buffer::fromVector({passes::kScene, "texture coordinates 1"}, scene.texcoords1, 0);
  colors_ = gl::Buffer::fromVector({passes::kScene, "vertex colours"}, scene.colors, 0);
  indices_ = gl::Buffer::fromVector({passes::kScene, "indices"}, scene.indices, 0);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vertexArray_ = gl::VertexArrayHandle(vao);
  struct Stream {
    const gl::Buffer& buffer;
    GLint components;
  };
  // Locations as in glsl/gbuffer.vert.
  const Stream streams[] = {{positions_, 3}, {normals_, 3}, {texcoords_, 2}, {texcoords1_, 2}, {colors_, 4}};
  for (GLuint i = 0; i < 5; ++i) {
    glVertexArrayVertexBuffer(vao, i, streams[i].buffer.id(), 0, GLsizei(streams[i].components * sizeof(float)));
    glEnableVertexArrayAttrib(vao, i);
    glVertexArrayAttribFormat(vao, i, streams[i].components, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, i, i);
  }
  glVertexArrayElementBuffer(vao, indices_.id());

  for (const Material& m : scene.materials) materials_.push_back(toGpu(m));
  sceneLights_ = scene.lights;
  for (const PunctualLight& l : scene.lights) lights_.push_back(toGpu(l));
  materialBuffer_ = gl::Buffer::fromVector({passes::kScene, "materials"}, materials_, 0);
  lightBuffer_ = gl::Buffer::fromVector({passes::kScene, "punctual lights"}, lights_,
                                        GL_DYNAMIC_STORAGE_BIT);  // setPunctualLight updates it

  std::vector<gpu::GpuSceneTriangle> triangles(scene.triangleCount());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const std::uint32_t* i = &scene.indices[3 * t];
    triangles[t] = {scene.triangleMaterials[t], i[0], i[1], i[2]};
  }
  sceneTriangles_ = gl::Buffer::fromVector({passes::kScene, "triangles"}, triangles, 0);
  std::vector<gpu::GpuSceneVertex> vertices(scene.positions.size());
  for (size_t v = 0; v < vertices.size(); ++v)
    vertices[v] = {glm::vec4(scene.texcoords[v], scene.texcoords1[v]), scene.colors[v]};
  sceneVertices_ = gl::Buffer::fromVector({passes::kScene, "vertex attributes"}, vertices, 0);
  std::vector<gpu::GpuTextureInfo> infos;
  std::vector<std::uint32_t> texels;
  packTexels(scene, infos, texels);
  textureInfos_ = gl::Buffer::fromVector({passes::kScene, "texture infos"}, infos, 0);
  texels_ = gl::Buffer::fromVector({passes::kScene, "texels"}, texels, 0);

  for (const Texture& t : scene.textures) textures_.push_back(uploadTexture(t));
  white_ = gl::Texture2D({passes::kScene, "white texture"}, 1, 1, GL_RGBA8);
  const std::uint8_t white[4] = {255, 255, 255, 255};
  white_.upload(GL_RGBA, GL_UNSIGNED_BYTE, white);
  gl::checkErrors("upload scene");
}

void SceneGpu::bindForCompute() const {
  gpuBvh_.bind();
  materialBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_MATERIALS);
  lightBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PUNCTUAL_LIGHTS);
  sceneTriangles_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_SCENE_TRIANGLES);
  sceneVertices_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_SCENE_VERTICES);
  textureInfos_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_TEXTURE_INFOS);
  texels_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_TEXELS);
}

void SceneGpu::setPunctualLight(size_t index, const PunctualLight& light) {
  if (index >= sceneLights_.size())
    throw std::out_of_range("SceneGpu::setPunctualLight: light " + std::to_string(index) + " of " +
                            std::to_string(sceneLights_.size()));
  uploadLight(index, light);
  ++lightsVersion_;
  gl::checkErrors("set punctual light");
}

void SceneGpu::uploadLight(size_t index, const PunctualLight& light) {
  sceneLights_[index] = light;
  lights_[index] = toGpu(light);
  lightBuffer_.update(&lights_[index], sizeof(gpu::GpuPunctualLight), index * sizeof(gpu::GpuPunctualLight));
}

void SceneGpu::follow(const PoseChange& change) {
  gl::DebugGroup group("follow the animation");
  for (size_t i : change.lights) uploadLight(i, scene_.lights.at(i));
  if (!change.lights.empty()) ++lightsVersion_;
  if (change.geometry) {
    positions_.update(scene_.positions);
    normals_.update(scene_.normals);
    buildBvh(bvh_.layout, kFollowBvhQuality);
    ++geometryVersion_;
  }
  gl::checkErrors("follow the animation");
}

const gl::Texture2D& SceneGpu::texture(int index) const {
  return index >= 0 && size_t(index) < textures_.size() ? textures_[size_t(index)] : white_;
}

}  // namespace lgh
