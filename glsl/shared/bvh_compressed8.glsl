// The compressed 8-wide BVH's traversal (shared/bvh_traverse.glsl includes it for
// gpu::kBvhLayoutCompressed8; Ylitie, Karras & Laine 2017): a node is five texels for eight children, whose
// boxes are decoded from their bytes (origin + q x step, exact but for one rounding, as bvh.cpp checked
// them) and slab-tested four at a time into a mask of the entered slots. The children are taken from
// the mask in slot order; entering a node leaves its parent's remaining slots on the stack, one entry per
// level (Ylitie et al.'s node groups), so the build's depth limit, kBvhStackSize - 1, bounds it. Closest-hit takes the
// children unordered: boxes entered before a nearer hit are still walked (correct, not the fastest).
#ifndef LGH_BVH_COMPRESSED8_GLSL
#define LGH_BVH_COMPRESSED8_GLSL

// The whole node from its integer view (the origin's bits are a float's, cast back exactly).
BvhCompressedNode bvhCompressedNode(uint index) {
  int texel = kBvhCompressedNodeTexels * int(index);
  uvec4 t0 = texelFetch(bvhNodeWords, texel), t1 = texelFetch(bvhNodeWords, texel + 1);
  return BvhCompressedNode(uintBitsToFloat(t0.xyz), t0.w, t1.x, t1.y, t1.zw, texelFetch(bvhNodeWords, texel + 2),
                           texelFetch(bvhNodeWords, texel + 3), texelFetch(bvhNodeWords, texel + 4));
}

// The four bytes of a word, low first, as floats.
vec4 bvhBytes(uint word) { return vec4((uvec4(word) >> uvec4(0u, 8u, 16u, 24u)) & 0xffu); }

// The entered children of a node, as a mask of its slots in use.
uint bvhEnteredChildren(BvhCompressedNode node, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  vec3 step = uintBitsToFloat(((uvec3(node.exponents) >> uvec3(0u, 8u, 16u)) & 0xffu) << 23u);
  uint entered = 0u;
  for (int h = 0; h < 2; ++h) {  // children 0-3, then 4-7
    vec4 x0 = (node.origin.x + bvhBytes(node.lowerXY[h]) * step.x - origin.x) * invDirection.x;
    vec4 y0 = (node.origin.y + bvhBytes(node.lowerXY[2 + h]) * step.y - origin.y) * invDirection.y;
    vec4 z0 = (node.origin.z + bvhBytes(node.lowerZUpperX[h]) * step.z - origin.z) * invDirection.z;
    vec4 x1 = (node.origin.x + bvhBytes(node.lowerZUpperX[2 + h]) * step.x - origin.x) * invDirection.x;
    vec4 y1 = (node.origin.y + bvhBytes(node.upperYZ[h]) * step.y - origin.y) * invDirection.y;
    vec4 z1 = (node.origin.z + bvhBytes(node.upperYZ[2 + h]) * step.z - origin.z) * invDirection.z;
    vec4 tEnter = max(max(min(x0, x1), min(y0, y1)), max(min(z0, z1), vec4(tMin)));
    vec4 tExit = min(min(max(x0, x1), max(y0, y1)), min(max(z0, z1), vec4(tMax)));
    uvec4 bits = uvec4(lessThanEqual(tEnter, tExit)) << uvec4(0u, 1u, 2u, 3u);
    entered |= (bits.x | bits.y | bits.z | bits.w) << (4u * uint(h));
  }
  return entered & (node.exponents >> 24u);  // the slots in use
}

// The walk: the node whose children are being taken, its header (childBase, triangleBase, meta) and
// the slots left; above it on bvhStack, one (node | slots << 24) per level.
struct BvhWalk {
  uint stackSize;
  uint group;
  uint slots;
  uvec4 header;
};

// Enters node `group`: its children's boxes tested into the slots to take.
void bvhWalkEnter(inout BvhWalk walk, uint group, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  BvhCompressedNode node = bvhCompressedNode(group);
  LGH_BVH_COUNT(bvhInnerNodes, 1u);
  LGH_BVH_COUNT(bvhBoxTests, 8u);
  walk.group = group;
  walk.slots = bvhEnteredChildren(node, origin, invDirection, tMin, tMax);
  walk.header = uvec4(node.childBase, node.triangleBase, node.meta);
}

bool bvhWalkStart(out BvhWalk walk, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  if (textureSize(bvhNodeWords) < kBvhCompressedNodeTexels) return false;  // no triangles (a stub buffer)
  walk.stackSize = 0u;
  bvhWalkEnter(walk, 0u, origin, invDirection, tMin, tMax);
  return true;
}

bool bvhWalkToLeaf(inout BvhWalk walk, vec3 origin, vec3 invDirection, float tMin, float tMax, bool anyHit,
                   out BvhLeafCursor leaf) {
  while (true) {
    if (walk.slots == 0u) {
      if (walk.stackSize == 0u) return false;
      uint entry = bvhStack[--walk.stackSize];
      walk.group = entry & kBvhCompressedNodeMask;
      walk.slots = entry >> 24u;
      walk.header = texelFetch(bvhNodeWords, kBvhCompressedNodeTexels * int(walk.group) + 1);
    }
    uint c = uint(findLSB(walk.slots));
    walk.slots &= walk.slots - 1u;
    uint meta = (walk.header[2u + (c >> 2u)] >> (8u * (c & 3u))) & 0xffu;
    if ((meta & kBvhMetaInner) == 0u) {
      leaf = BvhLeafCursor(walk.header.y + (meta & kBvhMetaOffsetMask), (meta >> kBvhMetaCountShift) + 1u);
      return true;
    }
    if (walk.slots != 0u) bvhStack[walk.stackSize++] = walk.group | walk.slots << 24u;
    bvhWalkEnter(walk, walk.header.x + (meta & kBvhMetaInnerIndexMask), origin, invDirection, tMin, tMax);
  }
  return false;  // not reached
}

#endif
