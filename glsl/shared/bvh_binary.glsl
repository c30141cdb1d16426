// The binary BVH's traversal (shared/bvh_traverse.glsl includes it for gpu::kBvhLayoutBinary): two child
// boxes a step, the nearer child first.
#ifndef LGH_BVH_BINARY_GLSL
#define LGH_BVH_BINARY_GLSL

// BvhNode `index`'s box, and its (firstChildOrTriangle, triangleCount).
void bvhNodeBounds(uint index, out vec3 boundsMin, out vec3 boundsMax) {
  boundsMin = texelFetch(bvhNodeFloats, kBvhNodeTexels * int(index)).xyz;
  boundsMax = texelFetch(bvhNodeFloats, kBvhNodeTexels * int(index) + 1).xyz;
}
uvec2 bvhNodeLinks(uint index) {
  return uvec2(texelFetch(bvhNodeWords, kBvhNodeTexels * int(index)).w,
               texelFetch(bvhNodeWords, kBvhNodeTexels * int(index) + 1).w);
}

// Slab test; returns the entry distance or +inf for a miss. Boxes are padded at build time, so a
// ray grazing a flat (axis-aligned) box still enters it despite rounding.
float bvhEnterBox(vec3 boundsMin, vec3 boundsMax, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  vec3 t0 = (boundsMin - origin) * invDirection;
  vec3 t1 = (boundsMax - origin) * invDirection;
  vec3 tSmall = min(t0, t1), tLarge = max(t0, t1);
  float tEnter = max(max(tSmall.x, tSmall.y), max(tSmall.z, tMin));
  float tExit = min(min(tLarge.x, tLarge.y), min(tLarge.z, tMax));
  return tEnter <= tExit ? tEnter : uintBitsToFloat(0x7f800000u);
}

float bvhEnterNode(uint index, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  vec3 boundsMin, boundsMax;
  bvhNodeBounds(index, boundsMin, boundsMax);
  return bvhEnterBox(boundsMin, boundsMax, origin, invDirection, tMin, tMax);
}

// The walk: the node to visit next (kBvhNoNode: the next one comes from bvhStack). The build keeps the
// depth below kBvhStackSize, and only one node is pushed per level, so the stack cannot overflow.
const uint kBvhNoNode = 0xffffffffu;
struct BvhWalk {
  uint stackSize;
  uint node;
};

bool bvhWalkStart(out BvhWalk walk, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  if (textureSize(bvhNodeFloats) < kBvhNodeTexels) return false;  // no triangles (a stub buffer)
  walk = BvhWalk(0u, 0u);
  return !isinf(bvhEnterNode(0u, origin, invDirection, tMin, tMax));
}

bool bvhWalkToLeaf(inout BvhWalk walk, vec3 origin, vec3 invDirection, float tMin, float tMax, bool anyHit,
                   out BvhLeafCursor leaf) {
  while (true) {
    if (walk.node == kBvhNoNode) {
      if (walk.stackSize == 0u) return false;
      walk.node = bvhStack[--walk.stackSize];
    }
    uvec2 links = bvhNodeLinks(walk.node);  // (firstChildOrTriangle, triangleCount)
    walk.node = kBvhNoNode;
    if (links.y > 0u) {
      leaf = BvhLeafCursor(links.x, links.y);
      return true;
    }
    uint left = links.x, right = left + 1u;
    LGH_BVH_COUNT(bvhInnerNodes, 1u);
    LGH_BVH_COUNT(bvhBoxTests, 2u);
    float tLeft = bvhEnterNode(left, origin, invDirection, tMin, tMax);
    float tRight = bvhEnterNode(right, origin, invDirection, tMin, tMax);
    bool hitLeft = !isinf(tLeft), hitRight = !isinf(tRight);
    if (hitLeft && hitRight) {
      // Nearer child first; the farther one waits on the stack.
      bool leftFirst = tLeft <= tRight;
      bvhStack[walk.stackSize++] = leftFirst ? right : left;
      walk.node = leftFirst ? left : right;
    } else if (hitLeft || hitRight) {
      walk.node = hitLeft ? left : right;
    }
  }
  return false;  // not reached
}

#endif
