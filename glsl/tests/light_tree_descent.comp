#version 450 core
// Test kernel: one descent of the light tree per invocation (shared/light_tree.glsl's descendToLeaf) from
// `startNode` at the fixed shading point (x, n), each with its own random numbers: the leaf reached (0 for
// a dead branch) and the probability the descent computed for it.
layout(local_size_x = 64) in;
#include "shared/bindings.h"
#include "shared/dispatch.glsl"
#include "shared/light_tree_types.h"
#include "shared/sampling.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Nodes { GpuLightTreeNode nodes[]; };
layout(std430, binding = LGH_BINDING_PASS1) writeonly buffer Leaves { uint leaves[]; };
layout(std430, binding = LGH_BINDING_PASS2) writeonly buffer Probabilities { float probabilities[]; };
#include "shared/light_tree.glsl"

uniform uint count, startNode, leafCount, seed;
uniform vec3 x, n;
uniform float clampDistance;

void main() {
  uint i = lghGlobalIndex();
  if (i >= count) return;
  Rng rng = makeRng(i, seed);
  float probability;
  leaves[i] = descendToLeaf(startNode, leafCount, x, n, clampDistance, rng, probability);
  probabilities[i] = probability;
}
