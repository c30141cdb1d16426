// Grid geometry and the vertex hash table of the GPU hierarchy build (render/passes/lgh_build_pass).
//
// Each level keeps only its occupied vertices: a hash table of vertex keys (open addressing, linear
// probing, capacity a power of two), compacted by a prefix sum into a dense list of grid lights.
// Insertion is "ordered" (Amble & Knuth): atomicMin keeps the smaller key and carries the larger one
// on, so the final table depends only on the set of keys, not on the order threads arrive in. That
// makes the compacted order, and so the whole build, deterministic.
#ifndef LGH_LGH_GRID_GLSL
#define LGH_LGH_GRID_GLSL
#include "shared/bindings.h"
#include "shared/color.glsl"
#include "shared/lgh_types.h"

layout(std140, binding = LGH_UBO_PASS) uniform GridParamsBlock { LghGridParams grid; };

vec3 gridOrigin() { return grid.originAndTopCell.xyz; }
float gridCellSize() { return grid.cellSizeAndScale.x; }        // h of the level being built
uint gridVerticesPerAxis() { return grid.levelsAndCounts.w; }    // cells + 1 at that level
uint tableMask() { return grid.table.y; }

// The cell of the level being built that contains p (clamped to the grid, as lgh::forEachCorner does)
// and p's position inside it, 0..1 per axis.
struct GridCell {
  uvec3 cell;
  vec3 t;
};
GridCell locateCell(vec3 p) {
  vec3 u = (p - gridOrigin()) / gridCellSize();
  vec3 c = clamp(floor(u), vec3(0.0), vec3(float(gridVerticesPerAxis() - 2u)));
  GridCell g;
  g.cell = uvec3(c);
  g.t = clamp(u - c, vec3(0.0), vec3(1.0));
  return g;
}
uvec3 cornerOffset(uint corner) { return uvec3(corner & 1u, (corner >> 1u) & 1u, (corner >> 2u) & 1u); }
float cornerWeight(vec3 t, uvec3 offset) {
  vec3 f = mix(vec3(1.0) - t, t, vec3(offset));
  return f.x * f.y * f.z;
}
vec3 vertexPosition(uvec3 v) { return gridOrigin() + vec3(v) * gridCellSize(); }
uint vertexKey(uvec3 v) { return v.x + gridVerticesPerAxis() * (v.y + gridVerticesPerAxis() * v.z); }
uvec3 keyVertex(uint key) {
  uint n = gridVerticesPerAxis();
  return uvec3(key % n, (key / n) % n, key / (n * n));
}

uint hashKey(uint k) {  // murmur3's finaliser: neighbouring vertices land far apart
  k ^= k >> 16u;
  k *= 0x85ebca6bu;
  k ^= k >> 13u;
  k *= 0xc2b2ae35u;
  k ^= k >> 16u;
  return k;
}

// Declares `uint name##Find(uint key)` (slot or kEmptyKey) for a table of mask + 1 slots. Lookup may
// stop at a larger key: ordered insertion leaves only smaller keys on a key's probe path (slots only
// ever decrease). `keys` may be readonly.
#define LGH_DEFINE_HASH_FIND(name, keys, mask)                          \
  uint name##Find(uint key) {                                           \
    uint slot = hashKey(key) & (mask);                                  \
    for (uint probe = 0u; probe <= (mask); ++probe) {                   \
      uint k = keys[slot];                                              \
      if (k == key) return slot;                                        \
      if (k > key) return kEmptyKey;                                    \
      slot = (slot + 1u) & (mask);                                      \
    }                                                                   \
    return kEmptyKey;                                                   \
  }

// Declares name##Find and `bool name##Insert(uint key)`: ordered insertion into keys[], counting new
// keys in counter[0] and setting counter[1] on overflow.
#define LGH_DEFINE_HASH_TABLE(name, keys, counter, mask)                \
  LGH_DEFINE_HASH_FIND(name, keys, mask)                                \
  bool name##Insert(uint key) {                                         \
    uint slot = hashKey(key) & (mask);                                  \
    for (uint probe = 0u; probe <= (mask); ++probe) {                   \
      uint old = atomicMin(keys[slot], key);                            \
      if (old == kEmptyKey) {                                           \
        atomicAdd(counter[0], 1u);                                      \
        return true;                                                    \
      }                                                                 \
      if (old == key) return true;                                      \
      key = max(key, old);                                              \
      slot = (slot + 1u) & (mask);                                      \
    }                                                                   \
    counter[1] = 1u;                                                    \
    return false;                                                       \
  }

// A grid light from its sums, all offsets in units of the cell size h relative to its vertex:
// W = lum(I) = sum w a, D = sum w a e, Q = sum w a (var/h^2 + e*e), N = sum w a n, O = sum w a [omni].
GpuGridLight makeGridLight(uint key, uint level, vec3 vertexPos, float h, vec3 I, vec3 D, vec3 Q, vec3 N, float O) {
  GpuGridLight light;
  float W = luminance(I);
  light.level = level;
  light.vertexKey = key;
  light.intensity = max(I, vec3(0.0));
  light.pad = 0u;
  if (!(W > 0.0)) {  // energy rounded away (only with intensities 1e-16 of the brightest): a dark light
    light.position = vertexPos;
    light.variance = vec3(0.0);
    light.meanNormal = vec3(0.0);
    light.omniFraction = 1.0;
    return light;
  }
  vec3 mean = D / W;
  light.position = vertexPos + h * mean;
  light.variance = h * h * max(Q / W - mean * mean, vec3(0.0));
  vec3 m = N / W;
  float mLength = length(m);
  light.meanNormal = mLength > 1.0 ? m / mLength : m;  // absorbs rounding only
  light.omniFraction = clamp(O / W, 0.0, 1.0);
  return light;
}

#endif
