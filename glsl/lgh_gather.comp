#version 450 core
// Builds one vertex of level l+1 from the grid lights of level l, without atomics: the vertex looks
// up the level-l vertices that can hold children for it (a child's centre lies within one cell of
// its own vertex, so only level-l vertices within 2 of 2V per axis qualify: 5^3 lookups) and sums
// those whose centre lies in one of its 8 cells, with the trilinear weight relative to it. A child
// brings its own variance, so the second moments stay exact (docs/design.md §2).
layout(local_size_x = 64) in;
#include "shared/dispatch.glsl"
#include "shared/lgh_grid.glsl"

layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Children { GpuGridLight children[]; };
layout(std430, binding = LGH_BINDING_PASS1) readonly buffer ChildKeys { uint childTableKeys[]; };
layout(std430, binding = LGH_BINDING_PASS2) readonly buffer ChildSlotIndex { uint childSlotIndex[]; };
layout(std430, binding = LGH_BINDING_PASS4) writeonly buffer Output { GpuGridLight gridLights[]; };
layout(std430, binding = LGH_BINDING_PASS7) readonly buffer CompactKeys { uint compactKeys[]; };
uniform uint vertexCount;
uniform uint childVerticesPerAxis;
uniform uint childTableMask;
LGH_DEFINE_HASH_FIND(childTable, childTableKeys, childTableMask)

void main() {
  uint index = lghGlobalIndex();
  if (index >= vertexCount) return;
  uint key = compactKeys[index];
  uvec3 V = keyVertex(key);
  vec3 vertexPos = vertexPosition(V);
  float h = gridCellSize();
  ivec3 lo = max(ivec3(2u * V) - 2, ivec3(0));
  ivec3 hi = min(ivec3(2u * V) + 2, ivec3(childVerticesPerAxis) - 1);

  float W = 0.0, O = 0.0;
  vec3 D = vec3(0.0), Q = vec3(0.0), I = vec3(0.0), N = vec3(0.0);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        uint childKey = uint(x) + childVerticesPerAxis * (uint(y) + childVerticesPerAxis * uint(z));
        uint slot = childTableFind(childKey);
        if (slot == kEmptyKey) continue;
        GpuGridLight child = children[childSlotIndex[slot]];
        float a = luminance(child.intensity);
        if (!(a > 0.0)) continue;
        GridCell c = locateCell(child.position);
        ivec3 offset = ivec3(V) - ivec3(c.cell);
        if (any(lessThan(offset, ivec3(0))) || any(greaterThan(offset, ivec3(1)))) continue;
        float w = cornerWeight(c.t, uvec3(offset));
        if (!(w > 0.0)) continue;
        float wa = w * a;
        vec3 e = (child.position - vertexPos) / h;
        D += wa * e;
        Q += wa * (child.variance / (h * h) + e * e);
        I += w * child.intensity;
        N += wa * child.meanNormal;
        O += wa * child.omniFraction;
      }
  gridLights[index] = makeGridLight(key, grid.levelsAndCounts.y, vertexPos, h, I, D, Q, N, O);
}
