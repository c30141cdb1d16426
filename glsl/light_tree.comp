#version 450 core
// The light tree's build (Lin & Yuksel 2020, §3.1 and §4; docs/design.md §12), one stage per dispatch,
// after the lights' bounds (lgh_bounds.comp) and around the radix sort (gl::RadixSort):
//   morton  each light's 30-bit Morton code in the lights' box (kMortonLevels per axis), keyed to its index
//   (sort)  the (code, index) pairs by code, stably: ties keep S0's order, so the tree is deterministic
//   leaves  leaf 2^(L-1) + i: the i-th sorted light, its luminance and its position as a point box;
//           padding leaves past the lights, and unlit lights, are empty (intensity 0, inverted box)
//   level   the nodes of one level from their children: intensities summed, boxes united
// The CPU reference (lgh/light_tree.cpp) does the same in the same order; the tests compare them.
layout(local_size_x = 256) in;
#include "shared/bindings.h"
#include "shared/color.glsl"
#include "shared/dispatch.glsl"
#include "shared/lgh_types.h"
#include "shared/light_tree_types.h"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = LGH_BINDING_PASS1) buffer Keys { uint keys[]; };      // Morton codes
layout(std430, binding = LGH_BINDING_PASS2) buffer Values { uint values[]; };  // S0 indices, sorted with the keys
layout(std430, binding = LGH_BINDING_PASS3) readonly buffer Bounds { LghBoundsResult bounds; };
layout(std430, binding = LGH_BINDING_PASS4) buffer Nodes { GpuLightTreeNode nodes[]; };

const uint kStageMorton = 0u, kStageLeaves = 1u, kStageLevel = 2u;  // LightTreePass's order
uniform uint stage;
uniform uint lightCount;
uniform uint leafCount;  // 2^(L-1)
uniform uint levelFirst;  // kStageLevel: the level's first node (and its node count)

// 10 bits spread to every third bit.
uint spreadBits(uint v) {
  v &= 0x3ffu;
  v = (v | (v << 16u)) & 0x030000ffu;
  v = (v | (v << 8u)) & 0x0300f00fu;
  v = (v | (v << 4u)) & 0x030c30c3u;
  v = (v | (v << 2u)) & 0x09249249u;
  return v;
}

// A position's cell in the lights' box, per axis, as lgh::mortonCode quantises it.
uint quantize(float p, float lower, float upper) {
  float extent = upper - lower;
  if (!(extent > 0.0)) return 0u;
  float t = (p - lower) * (float(kMortonLevels) / extent);
  return t >= float(kMortonLevels - 1u) ? kMortonLevels - 1u : uint(t);
}

GpuLightTreeNode emptyNode() {
  const float kFloatMax = uintBitsToFloat(0x7f7fffffu);
  return GpuLightTreeNode(vec3(kFloatMax), 0.0, vec3(-kFloatMax), kTreeNoLight);
}

void main() {
  uint i = lghGlobalIndex();
  if (stage == kStageMorton) {
    if (i >= lightCount) return;
    vec3 p = lights[i].position;
    uvec3 q;
    for (int a = 0; a < 3; ++a)
      q[a] = quantize(p[a], fromOrderedBits(bounds.allLower[a]), fromOrderedBits(bounds.allUpper[a]));
    keys[i] = (spreadBits(q.x) << 2u) | (spreadBits(q.y) << 1u) | spreadBits(q.z);
    values[i] = i;
  } else if (stage == kStageLeaves) {
    if (i >= leafCount) return;
    GpuLightTreeNode leaf = emptyNode();
    if (i < lightCount) {
      GpuLight light = lights[values[i]];
      leaf.lightIndex = values[i];
      leaf.intensity = max(luminance(light.intensity), 0.0);
      if (leaf.intensity > 0.0) {
        leaf.boundMin = light.position;
        leaf.boundMax = light.position;
      }
    }
    nodes[leafCount + i] = leaf;
  } else {
    if (i >= levelFirst) return;
    uint node = levelFirst + i;
    GpuLightTreeNode left = nodes[2u * node], right = nodes[2u * node + 1u];
    nodes[node] = GpuLightTreeNode(min(left.boundMin, right.boundMin), left.intensity + right.intensity,
                                   max(left.boundMax, right.boundMax), kTreeNoLight);
  }
}
