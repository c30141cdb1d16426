#version 450 core
#ifdef LGH_FLOAT_ATOMICS
#extension GL_NV_shader_atomic_float : require
#endif
// Turns the accumulated sums of a scattered level into grid lights, one per occupied vertex.
layout(local_size_x = 256) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"
#include "shared/lgh_accumulators.glsl"

layout(std430, binding = LGH_BINDING_PASS7) readonly buffer CompactKeys { uint compactKeys[]; };
layout(std430, binding = LGH_BINDING_PASS0) writeonly buffer Output { GpuGridLight gridLights[]; };
uniform uint vertexCount;

void main() {
  uint index = lghGlobalIndex();
  if (index >= vertexCount) return;
  uint key = compactKeys[index];
  vec3 D, Q, I, N;
  for (uint k = 0u; k < 3u; ++k) {
    D[k] = accPositionRead(6u * index + k);
    Q[k] = accPositionRead(6u * index + 3u + k);
    I[k] = accIntensityRead(3u * index + k);
    N[k] = accNormalRead(4u * index + k);
  }
  float O = accNormalRead(4u * index + 3u);
  gridLights[index] = makeGridLight(key, grid.levelsAndCounts.y, vertexPosition(keyVertex(key)), gridCellSize(),
                                    I, D, Q, N, O);
}
