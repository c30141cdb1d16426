#include "render/scene/scene_gpu.h"

#include <chrono>
#include <cmath>

#include "render/gl/debug.h"
#include "shared/bindings.h"

namespace lgh {
namespace {

gpu::GpuPunctualLight toGpu(const PunctualLight& light) {
  gpu::GpuPunctualLight g{};
  g.position = light.position;
  g.type = light.type == LightType::Point ? gpu::kLightPoint
           : light.type == LightType::Spot ? gpu::kLightSpot
                                           : gpu::kLightDirectional;
  g.direction = light.direction;
  g.range = light.range;
  g.intensity = light.intensity;
  g.innerConeCos = light.innerConeCos;
  g.outerConeCos = light.outerConeCos;
  return g;
}

gl::Texture2D uploadTexture(const Texture& texture) {
  const int levels = 1 + int(std::floor(std::log2(float(std::max(texture.width, texture.height)))));
  // Colour textures are sRGB-encoded in glTF; the sampler decodes them to linear.
  gl::Texture2D t(texture.width, texture.height, GL_SRGB8_ALPHA8, levels);
  t.upload(GL_RGBA, GL_UNSIGNED_BYTE, texture.rgba.data());
  glGenerateTextureMipmap(t.id());
  t.setFilter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  t.setWrap(GL_REPEAT);
  return t;
}

}  // namespace

SceneGpu::SceneGpu(const Scene& scene) : scene_(scene) {
  gl::DebugGroup group("upload scene");
  const auto start = std::chrono::steady_clock::now();
  bvh_ = buildBvh(scene.positions, scene.indices);
  bvhBuildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  positions_ = gl::Buffer::fromVector(scene.positions, 0);
  normals_ = gl::Buffer::fromVector(scene.normals, 0);
  texcoords_ = gl::Buffer::fromVector(scene.texcoords, 0);
  indices_ = gl::Buffer::fromVector(scene.indices, 0);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vertexArray_ = gl::VertexArrayHandle(vao);
  struct Stream {
    const gl::Buffer& buffer;
    GLint components;
  };
  const Stream streams[] = {{positions_, 3}, {normals_, 3}, {texcoords_, 2}};
  for (GLuint i = 0; i < 3; ++i) {
    glVertexArrayVertexBuffer(vao, i, streams[i].buffer.id(), 0, GLsizei(streams[i].components * sizeof(float)));
    glEnableVertexArrayAttrib(vao, i);
    glVertexArrayAttribFormat(vao, i, streams[i].components, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, i, i);
  }
  glVertexArrayElementBuffer(vao, indices_.id());

  for (const Material& m : scene.materials)
    materials_.push_back({m.baseColorFactor, m.emission, m.baseColorTexture, m.emissiveTexture, 0, 0, 0});
  for (const PunctualLight& l : scene.lights) lights_.push_back(toGpu(l));
  bvhNodes_ = gl::Buffer::fromVector(bvh_.nodes, 0);
  bvhTriangles_ = gl::Buffer::fromVector(bvh_.triangles, 0);
  materialBuffer_ = gl::Buffer::fromVector(materials_, 0);
  lightBuffer_ = gl::Buffer::fromVector(lights_, 0);

  for (const Texture& t : scene.textures) textures_.push_back(uploadTexture(t));
  white_ = gl::Texture2D(1, 1, GL_RGBA8);
  const std::uint8_t white[4] = {255, 255, 255, 255};
  white_.upload(GL_RGBA, GL_UNSIGNED_BYTE, white);
  gl::checkErrors("upload scene");
}

void SceneGpu::bindForCompute() const {
  bvhNodes_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_BVH_NODES);
  bvhTriangles_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_BVH_TRIANGLES);
  materialBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_MATERIALS);
  lightBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PUNCTUAL_LIGHTS);
}

const gl::Texture2D& SceneGpu::texture(int index) const {
  return index >= 0 && size_t(index) < textures_.size() ? textures_[size_t(index)] : white_;
}

}  // namespace lgh
