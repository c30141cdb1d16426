// The 4-wide BVH's traversal (shared/bvh_traverse.glsl includes it for gpu::kBvhLayoutWide4): one node's
// four child boxes in one slab test, and the children entered pushed, leaves as well as inner nodes, so
// that a leaf popped ends the steps over nodes (the loops of shared/bvh_traverse.glsl). (Testing a leaf child's
// triangles in the loop over the children made llvmpipe's invocations, which run as SIMD lanes, wait on each other's
// leaves four times a node: the frame's shadow rays took 2x as long; docs/measurements.md, "The BVH".) Any-hit (shadow
// rays) pushes them in node order and ends at the first hit; closest-hit pushes them farthest first, so the nearest is
// taken next and its hits shorten the others' boxes. The build keeps the depth within (kBvhStackSize - 4) / 3 levels,
// and a node pushes at most 4 entries for the one it pops, so the stack cannot overflow.
#ifndef LGH_BVH_WIDE4_GLSL
#define LGH_BVH_WIDE4_GLSL

BvhWideNode bvhWideNode(uint index) {
  int texel = kBvhWideNodeTexels * int(index);
  return BvhWideNode(texelFetch(bvhNodeFloats, texel), texelFetch(bvhNodeFloats, texel + 1),
                     texelFetch(bvhNodeFloats, texel + 2), texelFetch(bvhNodeFloats, texel + 3),
                     texelFetch(bvhNodeFloats, texel + 4), texelFetch(bvhNodeFloats, texel + 5),
                     texelFetch(bvhNodeWords, texel + 6));
}

// The walk: the entries on bvhStack (nodes, and leaves as kBvhLeaf | (count - 1) << kBvhLeafCountShift |
// first triangle).
struct BvhWalk {
  uint stackSize;
};

bool bvhWalkStart(out BvhWalk walk, vec3 origin, vec3 invDirection, float tMin, float tMax) {
  if (textureSize(bvhNodeFloats) < kBvhWideNodeTexels) return false;  // no triangles (a stub buffer)
  bvhStack[0] = 0u;
  walk = BvhWalk(1u);
  return true;
}

bool bvhWalkToLeaf(inout BvhWalk walk, vec3 origin, vec3 invDirection, float tMin, float tMax, bool anyHit,
                   out BvhLeafCursor leaf) {
  float enterOf[4];  // closest-hit: the entry distances of the children being pushed
  while (true) {
    if (walk.stackSize == 0u) return false;
    uint entry = bvhStack[--walk.stackSize];
    if ((entry & kBvhLeaf) != 0u) {
      leaf = BvhLeafCursor(entry & kBvhLeafFirstMask, ((entry >> kBvhLeafCountShift) & kBvhLeafCountMask) + 1u);
      return true;
    }
    BvhWideNode node = bvhWideNode(entry);
    LGH_BVH_COUNT(bvhInnerNodes, 1u);
    LGH_BVH_COUNT(bvhBoxTests, 4u);
    // Slab tests of the four children at once, against (tMin, tMax). (Differences first: lower x inv -
    // origin x inv would make inf - inf = NaN, a missed box, far from the origin along an axis-parallel ray.)
    vec4 x0 = (node.lowerX - origin.x) * invDirection.x, x1 = (node.upperX - origin.x) * invDirection.x;
    vec4 y0 = (node.lowerY - origin.y) * invDirection.y, y1 = (node.upperY - origin.y) * invDirection.y;
    vec4 z0 = (node.lowerZ - origin.z) * invDirection.z, z1 = (node.upperZ - origin.z) * invDirection.z;
    vec4 tEnter = max(max(min(x0, x1), min(y0, y1)), max(min(z0, z1), vec4(tMin)));
    vec4 tExit = min(min(max(x0, x1), max(y0, y1)), min(max(z0, z1), vec4(tMax)));
    bvec4 entered = lessThanEqual(tEnter, tExit);
    if (anyHit) {
      for (int c = 0; c < 4; ++c)
        if (entered[c] && node.children[c] != kBvhEmptyChild) bvhStack[walk.stackSize++] = node.children[c];
      continue;
    }
    // Closest-hit: the entered children pushed farthest first (insertion by entry distance).
    uint first = walk.stackSize;
    for (int c = 0; c < 4; ++c) {
      if (!entered[c] || node.children[c] == kBvhEmptyChild) continue;
      uint place = walk.stackSize++;
      while (place > first && enterOf[place - 1u - first] < tEnter[c]) {
        bvhStack[place] = bvhStack[place - 1u];
        enterOf[place - first] = enterOf[place - 1u - first];
        --place;
      }
      bvhStack[place] = node.children[c];
      enterOf[place - first] = tEnter[c];
    }
  }
  return false;  // not reached
}

#endif
