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

// Walks the BVH; with anyHit it stops at the first hit inside (tMin, tMax). The build keeps the depth
// below kBvhStackSize, and only one node is pushed per level, so the stack cannot overflow.
bool bvhTrace(vec3 origin, vec3 direction, float tMin, float tMax, bool anyHit, out RayHit hit) {
  hit = bvhNoHit(tMax);
  if (textureSize(bvhNodeFloats) < kBvhNodeTexels) return false;  // no triangles (a stub buffer)
  vec3 invDirection = bvhInverseDirection(direction);

  uint stack[kBvhStackSize];
  uint stackSize = 0u;
  uint node = 0u;
  if (isinf(bvhEnterNode(0u, origin, invDirection, tMin, tMax))) return false;
  bool found = false;
  while (true) {
    uvec2 links = bvhNodeLinks(node);  // (firstChildOrTriangle, triangleCount)
    if (links.y > 0u) {
      if (bvhTestLeaf(links.x, links.y, origin, direction, tMin, anyHit, hit)) {
        found = true;
        if (anyHit) return true;
      }
    } else {
      uint left = links.x, right = left + 1u;
      LGH_BVH_COUNT(bvhInnerNodes, 1u);
      LGH_BVH_COUNT(bvhBoxTests, 2u);
      float tLeft = bvhEnterNode(left, origin, invDirection, tMin, hit.t);
      float tRight = bvhEnterNode(right, origin, invDirection, tMin, hit.t);
      bool hitLeft = !isinf(tLeft), hitRight = !isinf(tRight);
      if (hitLeft && hitRight) {
        // Nearer child first; the farther one waits on the stack.
        bool leftFirst = tLeft <= tRight;
        stack[stackSize++] = leftFirst ? right : left;
        node = leftFirst ? left : right;
        continue;
      }
      if (hitLeft || hitRight) {
        node = hitLeft ? left : right;
        continue;
      }
    }
    if (stackSize == 0u) break;
    node = stack[--stackSize];
  }
  return found;
}

#endif
