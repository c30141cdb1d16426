#pragma once
// Generates the input lights S0 on the GPU:
//   tracePaths:             light paths from every emitter (chosen by power) through the BVH, an
//                           oriented VPL at each diffuse hit, up to `bounces` per path
//   sampleEmissiveTriangles: points on emissive triangles as oriented direct lights
//   in:  SceneGpu (BVH, materials, textures, punctual lights), the emitter tables built from the Scene
//   out: gpu::GpuLight records appended to a buffer from `offset` on, in an order that depends only on
//        the seed (sample i, or path p's bounces in order), not on the order GPU threads run in

#include <cstdint>

#include "render/gl/buffer.h"
#include "render/gl/prefix_sum.h"
#include "render/gl/program.h"
#include "render/pass_names.h"
#include "render/scene/emitters.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"

namespace lgh {

class VplPass {
 public:
  explicit VplPass(const SceneGpu& scene);

  // Traces ceil(budget / bounces) paths; each deposits at most `bounces` VPLs, so at most
  // maxVplCount(budget, bounces) are written (that many in a closed scene): `out` must have room for
  // them all. Returns the number written.
  size_t tracePaths(gl::Buffer& out, size_t offset, size_t budget, int bounces, std::uint32_t seed);
  // `count` points on emissive triangles (chosen by power). Returns the number written.
  size_t sampleEmissiveTriangles(gl::Buffer& out, size_t offset, size_t count, std::uint32_t seed);

  // The table of all emitters as of the last tracePaths (it follows SceneGpu's lights and geometry versions).
  const EmitterTable& emitters() const { return allEmitters_; }
  const EmitterTable& emissiveTriangles() const { return triangleEmitters_; }
  // At most this many samples per batch (0: as many as one storage block holds), for tests of the batching.
  void setBatchLimit(size_t samples) { batchLimit_ = samples; }
  static size_t pathCount(size_t budget, int bounces) { return (budget + size_t(bounces) - 1) / size_t(bounces); }
  static size_t maxVplCount(size_t budget, int bounces) { return pathCount(budget, bounces) * size_t(bounces); }

 private:
  void updateEmitters();  // rebuilds the emitter tables after the punctual lights or the vertices changed
  // Runs vpl_generate.comp for samples [first, first + count) of `total`: record `slot` of the batch's
  // count x `bounces` slots goes to out[offset + slot]. The batch's records must fit one storage block.
  void generate(const gl::Program& program, const gl::Buffer& emitters, gl::Buffer& out, size_t offset, size_t first,
                size_t count, size_t total, int bounces, std::uint32_t seed);
  // Moves the written records of `slotCount` slots to out[offset...], in slot order; returns their count.
  size_t compact(size_t slotCount, gl::Buffer& out, size_t offset);
  // Samples (paths, or emitter samples) per batch: their records, and the alignment a range binding of S0
  // may need in front of them, fit one storage block (S0 itself may not: it is written by ranges).
  size_t batchSamples(int bounces) const;

  const SceneGpu& scene_;
  EmitterTable allEmitters_, triangleEmitters_;
  gl::Buffer allEmitterBuffer_, triangleEmitterBuffer_;
  gl::Buffer pathSlots_, slotIndex_;  // the paths' fixed slots (GpuLight, flags 0: empty) and their compaction
  unsigned emittersLightsVersion_;    // SceneGpu::lightsVersion() that allEmitters_ was built from
  unsigned emittersGeometryVersion_;  // SceneGpu::geometryVersion() that both tables were built from
  size_t batchLimit_ = 0;
  TracingProgram paths_, emitterSamples_;
  gl::Program compactFlags_, compactWrite_;
  gl::PrefixSum prefixSum_{passes::kInputLights};
};

}  // namespace lgh
