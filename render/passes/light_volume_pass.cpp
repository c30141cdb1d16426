#include "render/passes/light_volume_pass.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/light_pass_types.h"

namespace lgh {

// One instanced draw: `count` lights from index `first` of the buffer bound at LGH_BINDING_PASS0.
struct LightVolumePass::Draw {
  const gl::Buffer* buffer = nullptr;
  bool s0Input = false;     // GpuLight (S0) rather than GpuGridLight
  bool fullScreen = false;  // a full-screen triangle per light rather than a cube
  size_t first = 0, count = 0;
  size_t boundOffset = 0, boundLights = 0;  // S0: the chunk bound (in lights); grid lights: whole buffer
};

size_t LightPassDraws::lightsDrawn() const {
  return std::accumulate(lightsPerLevel.begin(), lightsPerLevel.end(), size_t(0));
}

void ShadowSlots::allocate(glm::ivec2 targetSize, int samples) {
  if (samples < 0 || samples > int(gpu::kMaxShadowSamples))
    throw std::invalid_argument("shadow samples: " + std::to_string(samples) + " (use 0 to " +
                                std::to_string(gpu::kMaxShadowSamples) + ")");
  const size_t pixels = size_t(targetSize.x) * size_t(targetSize.y);
  gl::ensureSize(totals, std::max<size_t>(pixels, 1) * sizeof(float));
  gl::ensureSize(slots, std::max<size_t>(pixels * size_t(std::max(samples, 1)), 1) * sizeof(GLuint));
  k = samples;
  size = targetSize;
}

LightVolumePass::LightVolumePass(bool floatAtomics) : floatAtomics_(floatAtomics) {
  GLint alignment = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  uniformStride_ = (sizeof(gpu::LightPassUniforms) + size_t(alignment) - 1) / size_t(alignment) * size_t(alignment);
  GLint64 maxBlock = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  GLint ssboAlignment = 256;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &ssboAlignment);
  // Chunks start at multiples of this many lights, so every chunk's byte offset is aligned.
  const size_t lightsPerAlignment = std::max<size_t>(1, size_t(ssboAlignment) / sizeof(gpu::GpuLight));
  maxBlockLights_ = std::max<size_t>(size_t(std::max<GLint64>(maxBlock, 1 << 24)) / sizeof(gpu::GpuLight) /
                                         lightsPerAlignment * lightsPerAlignment,
                                     lightsPerAlignment);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  emptyVertexArray_ = gl::VertexArrayHandle(vao);
  gl::checkErrors("light pass setup");
}

const gl::Program& LightVolumePass::program(bool s0Input, const LightPassOptions& options) {
  gl::Defines defines;
  if (s0Input) defines.emplace_back("LGH_S0_INPUT", "1");
  if (options.pass.overdraw) defines.emplace_back("LGH_COUNT_OVERDRAW", "1");
  if (options.shadows.samples > 0) {
    defines.emplace_back("LGH_SELECT_SHADOWS", "1");
    if (!floatAtomics_) defines.emplace_back("LGH_SELECTION_NO_ATOMICS", "1");
  }
  std::string key;
  for (const auto& d : defines) key += d.first + ";";
  gl::Program& p = programs_[key];
  if (!p) p = gl::Program::graphics("light_volume.vert", "light_volume.frag", defines);
  return p;
}

LightPassDraws LightVolumePass::execute(const gl::Buffer& lights, size_t lightCount, const GpuHierarchy& hierarchy,
                                        const LightPassOptions& options, LightPassTarget& target) {
  if (options.pass.overdraw && !target.fragmentCounts)
    throw std::invalid_argument("light pass: counting fragments needs a fragment-count target");
  if (options.shadows.samples > 0 &&
      (!target.shadowSlots || target.shadowSlots->k != options.shadows.samples ||
       target.shadowSlots->size != target.layout.targetSize()))
    throw std::invalid_argument("light pass: shadow selection needs slots allocated for the target and k");
  if (options.pass.startLevel != 0 && options.pass.startLevel != 1)
    throw std::invalid_argument("light pass: the first level is 0 (S0) or 1 (S1), not " +
                                std::to_string(options.pass.startLevel));
  // Brute force draws no grid level; an unbuilt hierarchy has none either.
  const int L = options.pass.bruteForce || hierarchy.levels.empty() ? 0 : hierarchy.grid.levels;
  if (L > int(gpu::kMaxLightPassLevels) - 1)
    throw std::invalid_argument("light pass: " + std::to_string(L) + " levels, at most " +
                                std::to_string(gpu::kMaxLightPassLevels - 1) + " supported");

  // The draws of this frame, finest level first.
  std::vector<Draw> draws;
  LightPassDraws counts;
  counts.lightsPerLevel.assign(size_t(std::max(L, 0)) + 1, 0);
  const bool drawS0 = options.pass.bruteForce || (options.pass.startLevel == 0 && L >= 1);
  if (L >= 1 && hierarchy.levels.size() < size_t(L) + 1) throw std::logic_error("light pass: the hierarchy's level table is incomplete");
  if (drawS0) {
    for (size_t first = 0; first < lightCount; first += maxBlockLights_) {
      const size_t n = std::min(maxBlockLights_, lightCount - first);
      draws.push_back({&lights, true, options.pass.bruteForce, 0, n, first, n});
    }
    counts.lightsPerLevel[0] = lightCount;
  }
  if (!options.pass.bruteForce && L >= 1) {
    // Levels 1..L-1 are contiguous in the merged buffer: one instanced draw of cubes.
    const size_t gridLights = hierarchy.gridLightCount;
    const size_t cubesEnd = hierarchy.levels[size_t(L)].offset;
    if (L > 1 && cubesEnd > hierarchy.levels[1].offset)
      draws.push_back({&hierarchy.gridLights, false, false, hierarchy.levels[1].offset, cubesEnd - hierarchy.levels[1].offset, 0, gridLights});
    if (hierarchy.levels[size_t(L)].count > 0)
      draws.push_back({&hierarchy.gridLights, false, true, cubesEnd, hierarchy.levels[size_t(L)].count, 0, gridLights});
    for (int l = 1; l <= L; ++l) counts.lightsPerLevel[size_t(l)] = hierarchy.levels[size_t(l)].count;
  }

  // Per-draw uniforms, all uploaded before the first draw.
  gl::ensureSize(uniforms_, std::max<size_t>(draws.size(), 1) * uniformStride_);
  std::vector<unsigned char> staging(std::max<size_t>(draws.size(), 1) * uniformStride_, 0);
  const int n = target.layout.tilesPerAxis;
  for (size_t i = 0; i < draws.size(); ++i) {
    const Draw& d = draws[i];
    gpu::LightPassUniforms u{};
    u.alphaTopCellClampScale = glm::vec4(options.pass.alpha, float(hierarchy.grid.topCellSize), options.clampDistance,
                                         float(n * n));
    u.levels = glm::uvec4(unsigned(options.pass.startLevel), unsigned(std::max(L, 0)), unsigned(d.first),
                          unsigned(d.fullScreen));
    u.tiles = glm::uvec4(unsigned(n), unsigned(target.layout.tileSize.x), unsigned(target.layout.tileSize.y),
                         unsigned(d.boundOffset));
    u.image = glm::uvec4(unsigned(target.layout.imageSize.x), unsigned(target.layout.imageSize.y),
                         unsigned(options.pass.bruteForce), 0u);
    for (int l = 1; l <= L; ++l) u.levelOffsets[l / 4][l % 4] = unsigned(hierarchy.levels[size_t(l)].offset);
    u.selection = glm::uvec4(unsigned(options.shadows.samples),
                             (options.shadows.skipFinest ? gpu::kSelectSkipFinest : 0u) |
                                 (options.shadows.uniform ? gpu::kSelectUniform : 0u),
                             options.frameSeed, 0u);
    std::memcpy(staging.data() + i * uniformStride_, &u, sizeof(u));
  }
  uniforms_.update(staging.data(), staging.size());

  // Fixed state: additive blending, no depth, one back face per covered pixel, clipped to the tile.
  gl::Framebuffer framebuffer({&target.irradiance}, nullptr);
  framebuffer.bind();
  const glm::ivec2 size = target.layout.targetSize();
  glViewport(0, 0, size.x, size.y);
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, zero);
  if (options.pass.overdraw) {
    target.fragmentCounts->clearUint(0);
    target.fragmentCounts->bindImage(0, GL_READ_WRITE);
  }
  if (options.shadows.samples > 0) {
    target.shadowSlots->totals.clear();
    target.shadowSlots->slots.clearUint(gpu::kNoLight);
    target.shadowSlots->totals.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
    target.shadowSlots->slots.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  }
  target.position.bindTexture(0);
  target.normal.bindTexture(1);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  for (int c = 0; c < 4; ++c) glEnable(GL_CLIP_DISTANCE0 + c);
  glFrontFace(GL_CCW);
  glCullFace(GL_FRONT);
  glBindVertexArray(emptyVertexArray_.id());

  for (size_t i = 0; i < draws.size(); ++i) {
    const Draw& d = draws[i];
    const size_t stride = d.s0Input ? sizeof(gpu::GpuLight) : sizeof(gpu::GpuGridLight);
    d.buffer->bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, d.boundOffset * stride, d.boundLights * stride);
    uniforms_.bindRange(GL_UNIFORM_BUFFER, LGH_UBO_PASS, i * uniformStride_, sizeof(gpu::LightPassUniforms));
    program(d.s0Input, options).use();
    // Cubes cull their front faces; the full-screen triangle faces the camera and must not be culled.
    if (d.fullScreen)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    glDrawArraysInstanced(GL_TRIANGLES, 0, d.fullScreen ? 3 : 36, GLsizei(d.count));
  }

  glBindVertexArray(0);
  for (int c = 0; c < 4; ++c) glDisable(GL_CLIP_DISTANCE0 + c);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  gl::checkErrors("light pass");
  return counts;
}

}  // namespace lgh
