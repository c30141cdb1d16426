#include "render/passes/light_volume_pass.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/light_pass_types.h"

namespace lgh {

// One instanced draw: `count` lights from index `first` of the buffer bound at LGH_BINDING_PASS0.
struct LightVolumePass::Draw {
  const gl::Buffer* buffer = nullptr;
  bool s0Input = false;               // GpuLight (S0) rather than GpuGridLight
  unsigned shape = gpu::kVolumeCube;  // gpu::kVolume*
  bool sortedBySlice = false;         // culled grid lights: drawn slice by slice (VolumeCulling)
  size_t first = 0, count = 0;
  size_t boundOffset = 0, boundLights = 0;  // S0: the chunk bound (in lights); grid lights: whole buffer
};

namespace {

// Vertices per instance and primitive of each volume shape (light_volume.vert).
GLsizei verticesOf(unsigned shape) { return shape == gpu::kVolumeFullScreen ? 3 : shape == gpu::kVolumeCube ? 36 : 8; }
GLenum primitiveOf(unsigned shape) { return shape == gpu::kVolumeCulled ? GL_TRIANGLE_STRIP : GL_TRIANGLES; }

}  // namespace

size_t LightPassDraws::lightsDrawn() const {
  return std::accumulate(lightsPerLevel.begin(), lightsPerLevel.end(), size_t(0));
}

void ShadowSlots::allocate(glm::ivec2 targetSize, int samples) {
  if (samples < 0 || samples > int(gpu::kMaxShadowSamples))
    throw std::invalid_argument("shadow samples: " + std::to_string(samples) + " (use 0 to " +
                                std::to_string(gpu::kMaxShadowSamples) + ")");
  const size_t pixels = size_t(targetSize.x) * size_t(targetSize.y);
  // The shadow rays' inputs: their memory is the rays' (a fixed footprint per pixel and sample).
  const char* scaled = "width x height (x shadow-samples)";
  gl::fitSize(totals, {passes::kShadowRays, "slots: importance totals", scaled},
              std::max<size_t>(pixels, 1) * sizeof(float));
  gl::fitSize(unselectable, {passes::kShadowRays, "slots: unselectable", scaled},
              std::max<size_t>(pixels, 1) * sizeof(float));
  gl::fitSize(slots, {passes::kShadowRays, "slots: selected lights", scaled},
              std::max<size_t>(pixels * size_t(std::max(samples, 1)), 1) * sizeof(GLuint));
  k = samples;
  size = targetSize;
}

unsigned selectionFlags(const ShadowEstimator& shadows) {
  return (shadows.skipFinest ? gpu::kSelectSkipFinest : 0u) | (shadows.uniformSelection ? gpu::kSelectUniform : 0u) |
         (shadows.blendTargets ? gpu::kSelectBlendTargets : 0u);
}

LightVolumePass::LightVolumePass(bool floatAtomics)
    : floatAtomics_(floatAtomics), uniforms_(passes::kLightPass, sizeof(gpu::LightPassUniforms)) {
  maxBlockLights_ = gl::storageBlockElements(sizeof(gpu::GpuLight));  // chunks of S0 start aligned
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  emptyVertexArray_ = gl::VertexArrayHandle(vao);
  gl::checkErrors("light pass setup");
}

const gl::Program& LightVolumePass::program(const Draw& draw, const LightPassOptions& options, bool countUnselectable) {
  gl::Defines defines;
  if (draw.s0Input) defines.emplace_back("LGH_S0_INPUT", "1");
  if (draw.shape == gpu::kVolumeCulled) defines.emplace_back("LGH_DEPTH_CULLED", "1");
  if (draw.sortedBySlice) defines.emplace_back("LGH_SORTED_LIGHTS", "1");
  if (options.pass.overdraw) defines.emplace_back("LGH_COUNT_OVERDRAW", "1");
  if (options.shadows.samples > 0) {
    defines.emplace_back("LGH_SELECT_SHADOWS", "1");
    if (!floatAtomics_) defines.emplace_back("LGH_SELECTION_NO_ATOMICS", "1");
    if (countUnselectable && !draw.s0Input) defines.emplace_back("LGH_COUNT_UNSELECTABLE", "1");
  }
  std::string key;
  for (const auto& d : defines) key += d.first + ";";
  gl::Program& p = programs_[key];
  if (!p) p = gl::Program::graphics("light_volume.vert", "light_volume.frag", defines);
  return p;
}

void LightVolumePass::checkTarget(const LightPassOptions& options, const LightPassTarget& target, int levels) {
  if (options.pass.overdraw && !target.fragmentCounts)
    throw std::invalid_argument("light pass: counting fragments needs a fragment-count target");
  if (options.shadows.samples > 0 && (!target.shadowSlots || target.shadowSlots->k != options.shadows.samples ||
                                      target.shadowSlots->size != target.layout.targetSize()))
    throw std::invalid_argument("light pass: shadow selection needs slots allocated for the target and k");
  if (options.pass.startLevel != 0 && options.pass.startLevel != 1)
    throw std::invalid_argument("light pass: the first level is 0 (S0) or 1 (S1), not " +
                                std::to_string(options.pass.startLevel));
  if (levels > int(gpu::kMaxLightPassLevels) - 1)
    throw std::invalid_argument("light pass: " + std::to_string(levels) + " levels, at most " +
                                std::to_string(gpu::kMaxLightPassLevels - 1) + " supported");
}

// The unselectable grid lights are counted through the drawn targets when the estimator asks for it and
// there are grid lights and targets. The fragments read any input light, so they must fit one storage
// block: resolveShadowEstimator switches the counting off (and says so) when they do not.
unsigned LightVolumePass::unselectableTargets(const LightPassOptions& options, size_t lightCount, int L,
                                              const ShadowTargets* drawnTargets) const {
  const bool counts = options.shadows.countUnselectable && L >= 1 && drawnTargets && drawnTargets->races > 0;
  if (counts && lightCount > maxBlockLights_)
    throw std::invalid_argument("light pass: counting the unselectable grid lights needs the " +
                                std::to_string(lightCount) + " input lights in one storage block (at most " +
                                std::to_string(maxBlockLights_) + ")");
  return counts ? drawnTargets->races : 0u;
}

void LightVolumePass::release() {
  culling_.release();
  uniforms_.release();
  framebuffer_ = {};
}

LightPassDraws LightVolumePass::execute(const LightPassInputs& in, const LightPassOptions& options,
                                        const LightPassTarget& target) {
  const GpuHierarchy& hierarchy = in.hierarchy;
  // Brute force draws no grid level; an unbuilt hierarchy has none either.
  const int L = options.pass.bruteForce || hierarchy.levels.empty() ? 0 : hierarchy.grid.levels;
  checkTarget(options, target, L);
  LightPassDraws counts;
  const std::vector<Draw> draws = drawList(in.lights, in.lightCount, hierarchy, options, L, counts);
  const unsigned m = unselectableTargets(options, in.lightCount, L, in.drawnTargets);
  uploadUniforms(draws, hierarchy, options, target.layout, L, m);
  bindTargets(options, target);
  if (options.pass.volumeCulling) prepareCulling(draws, hierarchy, options, target, L);
  bindInputs(options, target, in.lights, in.lightCount, m > 0 ? in.drawnTargets : nullptr);
  issueDraws(draws, options, m > 0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  gl::checkErrors("light pass");
  return counts;
}

// The draws of this frame, finest level first: S0 in chunks of one storage block (brute force, or
// the first level 0), levels 1..L-1 as one instanced draw of volumes, the top level full-screen.
std::vector<LightVolumePass::Draw> LightVolumePass::drawList(const gl::Buffer& lights, size_t lightCount,
                                                             const GpuHierarchy& hierarchy,
                                                             const LightPassOptions& options, int L,
                                                             LightPassDraws& counts) const {
  std::vector<Draw> draws;
  counts.lightsPerLevel.assign(size_t(std::max(L, 0)) + 1, 0);
  const unsigned volume = options.pass.volumeCulling ? gpu::kVolumeCulled : gpu::kVolumeCube;
  const bool drawS0 = options.pass.bruteForce || (options.pass.startLevel == 0 && L >= 1);
  if (L >= 1 && hierarchy.levels.size() < size_t(L) + 1)
    throw std::logic_error("light pass: the hierarchy's level table is incomplete");
  if (drawS0) {
    const unsigned shape = options.pass.bruteForce ? gpu::kVolumeFullScreen : volume;
    for (size_t first = 0; first < lightCount; first += maxBlockLights_) {
      const size_t n = std::min(maxBlockLights_, lightCount - first);
      draws.push_back({&lights, true, shape, false, 0, n, first, n});
    }
    counts.lightsPerLevel[0] = lightCount;
  }
  if (!options.pass.bruteForce && L >= 1) {
    // Levels 1..L-1 are contiguous in the merged buffer: one instanced draw of volumes.
    const size_t gridLights = hierarchy.gridLightCount;
    const size_t volumesEnd = hierarchy.levels[size_t(L)].offset;
    if (L > 1 && volumesEnd > hierarchy.levels[1].offset)
      draws.push_back({&hierarchy.gridLights, false, volume, volume == gpu::kVolumeCulled, hierarchy.levels[1].offset,
                       volumesEnd - hierarchy.levels[1].offset, 0, gridLights});
    if (hierarchy.levels[size_t(L)].count > 0)
      draws.push_back({&hierarchy.gridLights, false, gpu::kVolumeFullScreen, false, volumesEnd,
                       hierarchy.levels[size_t(L)].count, 0, gridLights});
    for (int l = 1; l <= L; ++l) counts.lightsPerLevel[size_t(l)] = hierarchy.levels[size_t(l)].count;
  }
  return draws;
}

// Per-draw uniforms, all uploaded before the first draw.
void LightVolumePass::uploadUniforms(const std::vector<Draw>& draws, const GpuHierarchy& hierarchy,
                                     const LightPassOptions& options, const TileLayout& layout, int L,
                                     unsigned drawnTargets) {
  std::vector<gpu::LightPassUniforms> blocks(draws.size());
  const int n = layout.tilesPerAxis;
  for (size_t i = 0; i < draws.size(); ++i) {
    const Draw& d = draws[i];
    gpu::LightPassUniforms& u = blocks[i];
    u.alpha = options.pass.alpha;
    u.topCellSize = float(hierarchy.grid.topCellSize);
    u.clampDistance = options.clampDistance;
    u.contributionScale = float(n * n);
    u.firstLevel = unsigned(options.pass.startLevel);
    u.levels = unsigned(std::max(L, 0));
    u.instanceOffset = unsigned(d.first);
    u.volumeShape = d.shape;
    u.tilesPerAxis = unsigned(n);
    u.tileWidth = unsigned(layout.tileSize.x);
    u.tileHeight = unsigned(layout.tileSize.y);
    u.boundLightOffset = unsigned(d.boundOffset);
    u.imageWidth = unsigned(layout.imageSize.x);
    u.imageHeight = unsigned(layout.imageSize.y);
    u.bruteForce = options.pass.bruteForce ? 1u : 0u;
    u.cullingDepthScale = options.sceneSize;
    u.shadowSamples = unsigned(options.shadows.samples);
    u.selectFlags = selectionFlags(options.shadows);
    u.drawnTargets = drawnTargets;
    u.frameSeed = options.frameSeed;
    u.tileRotation = options.tileRotation % unsigned(n * n);
    u.defensive = options.shadows.defensive;
    for (int l = 1; l <= L; ++l) u.levelOffsets[l / 4][l % 4] = unsigned(hierarchy.levels[size_t(l)].offset);
  }
  uniforms_.upload(blocks);
}

// Clears and binds what the fragments write (irradiance, fragment counts, shadow slots) and read (the
// surfaces); with volume culling the framebuffer also holds the culling depth and slices.
void LightVolumePass::bindTargets(const LightPassOptions& options, const LightPassTarget& target) {
  const glm::ivec2 size = target.layout.targetSize();
  // Made per frame (the targets may change) and kept until the next: deleting a bound framebuffer unbinds it.
  framebuffer_ =
      gl::Framebuffer({&target.irradiance}, options.pass.volumeCulling ? &culling_.depthStencil(size) : nullptr);
  framebuffer_.bind();
  glViewport(0, 0, size.x, size.y);
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, zero);
  if (options.pass.overdraw) target.fragmentCounts->clearUint(0);
  if (options.shadows.samples > 0) {
    target.shadowSlots->totals.clear();
    target.shadowSlots->unselectable.clear();
    target.shadowSlots->slots.clearUint(gpu::kNoLight);
  }
}

// The culling depth, slices and pyramid from the surfaces, and the culled grid lights sorted by slice.
void LightVolumePass::prepareCulling(const std::vector<Draw>& draws, const GpuHierarchy& hierarchy,
                                     const LightPassOptions& options, const LightPassTarget& target, int L) {
  culling_.prepare(target.position, options.sceneSize);
  for (const Draw& d : draws)
    if (d.sortedBySlice)
      culling_.sortBySlice(
          {d.buffer, d.first, d.count, options.pass.alpha, float(hierarchy.grid.topCellSize), options.sceneSize, L});
}

// What the light volumes read and write besides the framebuffer; after the culling preparation, which
// uses image units, textures and storage bindings of its own.
void LightVolumePass::bindInputs(const LightPassOptions& options, const LightPassTarget& target,
                                 const gl::Buffer& lights, size_t lightCount, const ShadowTargets* drawnTargets) {
  if (options.pass.overdraw) target.fragmentCounts->bindImage(LGH_IMAGE_FRAGMENT_COUNTS, GL_READ_WRITE);
  if (options.shadows.samples > 0) {
    target.shadowSlots->totals.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
    target.shadowSlots->slots.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
    target.shadowSlots->unselectable.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
    if (drawnTargets) {  // counting the unselectable grid lights (the input lights fit one block)
      drawnTargets->targets.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
      lights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS5, 0, lightCount * sizeof(gpu::GpuLight));
    }
  }
  target.position.bindTexture(LGH_TEXTURE_SURFACE_POSITION);
  target.normal.bindTexture(LGH_TEXTURE_SURFACE_NORMAL);
  if (options.pass.volumeCulling) culling_.bindPyramid();
}

// Additive blending, one fragment per covered pixel (cubes and icosahedra cull their front faces;
// octagons and the full-screen triangle face the camera), clipped to the light's tile. Culled volumes
// pass the depth test only where the surface is not behind the volume (LEQUAL: volumeDepth is reversed)
// and, sorted by slice, the stencil test only where it is not in front of the sphere's slice. Depth in
// GL_ZERO_TO_ONE (shared/light_levels.h, volumeDepth); cubes and the full-screen triangle sit at z = 0.
void LightVolumePass::issueDraws(const std::vector<Draw>& draws, const LightPassOptions& options,
                                 bool countUnselectable) {
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LEQUAL);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  for (int c = 0; c < 4; ++c) glEnable(GL_CLIP_DISTANCE0 + c);
  glFrontFace(GL_CCW);
  glCullFace(GL_FRONT);
  for (size_t i = 0; i < draws.size(); ++i) {
    const Draw& d = draws[i];
    const size_t stride = d.s0Input ? sizeof(gpu::GpuLight) : sizeof(gpu::GpuGridLight);
    d.buffer->bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, d.boundOffset * stride, d.boundLights * stride);
    uniforms_.bind(i, LGH_UBO_PASS);
    program(d, options, countUnselectable).use();
    if (d.shape == gpu::kVolumeCube)
      glEnable(GL_CULL_FACE);
    else
      glDisable(GL_CULL_FACE);
    if (d.shape == gpu::kVolumeCulled)
      glEnable(GL_DEPTH_TEST);
    else
      glDisable(GL_DEPTH_TEST);
    if (d.sortedBySlice) {
      culling_.drawSorted();
    } else {
      glBindVertexArray(emptyVertexArray_.id());
      glDrawArraysInstanced(primitiveOf(d.shape), 0, verticesOf(d.shape), GLsizei(d.count));
    }
  }
  glBindVertexArray(0);
  for (int c = 0; c < 4; ++c) glDisable(GL_CLIP_DISTANCE0 + c);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);  // other passes use GL's default
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace lgh
