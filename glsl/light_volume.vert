#version 450 core
// One light per instance, drawn as its light volume: the region where its blending weight can be
// non-zero, d < 2R. Three shapes (pass.volumeShape):
//   full screen  the top level and brute force (weight non-zero at any distance): one triangle;
//   cube         the paper's cube of half-size 2R, 36 vertices, no depth test;
//   culled       the screen octagon that bounds the 2R sphere (8 vertices, a strip), at the depth
//                of the sphere's far side: the depth test against the surfaces (light_depth.frag)
//                rejects every pixel whose surface lies behind the sphere before it is shaded; and
//                not drawn at all when every surface under the rectangle lies in front of the
//                sphere (the light is hidden), read from a max-depth pyramid (light_depth_pyramid.comp).
//                Grid lights come sorted by the depth slice of their sphere's near side and are drawn
//                with that slice as stencil reference: pixels whose surface lies in a nearer slice
//                are rejected before shading too (render/passes/volume_culling.h). Depths are
//                volumeDepth (shared/light_levels.h), drawn with GL_ZERO_TO_ONE.
//   crossing     sorted grid lights whose sphere reaches the eye plane (flagged kCrossingVolume):
//                the 20 triangles of an icosahedron around the sphere, back faces kept, each at its
//                own volumeDepth, so that a pixel is shaded only where its surface is not behind
//                the icosahedron's far side.
// With n x n interleaving the light is drawn into one tile only: its clip-space position is mapped
// into that tile's block of the de-interleaved target and clipped to it with four clip distances.
#include "shared/bindings.h"
#include "shared/frame.glsl"
#include "shared/light_pass_types.h"
#include "shared/light_levels.h"

layout(std140, binding = LGH_UBO_PASS) uniform LightPass { LightPassUniforms pass; };
#ifdef LGH_S0_INPUT
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer Lights { GpuLight lights[]; };
#else
layout(std430, binding = LGH_BINDING_PASS0) readonly buffer GridLights { GpuGridLight lights[]; };
#endif
#ifdef LGH_SORTED_LIGHTS
// Culled grid lights drawn slice by slice (VolumeCulling::drawSorted): the light's index in the buffer,
// with kCrossingVolume set for lights drawn as icosahedra.
layout(location = 0) in uint sortedLightIndex;
#endif
// Deepest culling depth of the surfaces per texel of each level, in the target's (tiled) layout.
layout(binding = LGH_TEXTURE_SURFACE_DEPTH_PYRAMID) uniform sampler2D surfaceDepthPyramid;

out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[4];
};
flat out vec3 lightPosition;
flat out vec3 lightIntensity;
flat out vec4 lightLobe;    // xyz mean normal, w omni fraction
flat out vec2 lightBlend;   // x: R, y: role
flat out uint lightId;      // for shadow-sample selection: kSlotS0 | S0 index, or grid-light index
flat out vec3 lightVariance;  // per-axis variance of the cluster's lights about its centre (0 for S0)

// 12 triangles of the unit cube [-1,1]^3, counter-clockwise seen from outside: culling front faces
// leaves exactly one (back) face under every covered pixel, also with the camera inside the cube.
const uint kCubeIndices[36] = uint[](0u, 2u, 1u, 1u, 2u, 3u, 4u, 5u, 6u, 5u, 7u, 6u, 0u, 1u, 4u, 1u, 5u, 4u,
                                     2u, 6u, 3u, 3u, 6u, 7u, 0u, 4u, 2u, 2u, 4u, 6u, 1u, 3u, 5u, 3u, 7u, 5u);

// Relative widening of the culled volume: the rectangle and the far depth are computed in float in
// another order than the surfaces' depth, and the weight at the edge (d -> 2R) is ~0 anyway.
const float kCullingMargin = 1e-3;

vec4 fullScreenCorner() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  return vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}

vec4 cubeCorner(float radius) {
  uint c = kCubeIndices[gl_VertexID];
  vec3 corner = vec3(float(c & 1u), float((c >> 1u) & 1u), float((c >> 2u) & 1u)) * 2.0 - 1.0;
  vec4 clip = frame.viewProjection * vec4(lightPosition + radius * corner, 1.0);
  clip.z = 0.0;  // no depth test; never clipped by near/far as long as w > 0
  return clip;
}

// Where a light's tile lies in the target: target NDC = scale * full-resolution NDC + offset (w = 1),
// and the tile's block [lo, hi] in target NDC.
struct TileMap {
  vec2 scale, offset, lo, hi;
};

// Interleaving: this light belongs to tile ((k + rotation) mod n^2) of its level, k its index within
// the level.
TileMap tileOf(uint index, uint level) {
  uint n = pass.tilesPerAxis;
  uint levelStart = pass.levelOffsets[level / 4u][level % 4u];
  uint tile = (index + pass.boundLightOffset - levelStart + pass.tileRotation) % (n * n);
  vec2 t = vec2(float(tile % n), float(tile / n));
  vec2 tileSize = vec2(pass.tileWidth, pass.tileHeight), full = vec2(pass.imageWidth, pass.imageHeight);
  // Full-resolution window x maps to tile-local x' = (x - t - 0.5) / n + 0.5, placed at t * tileSize.
  TileMap m;
  m.scale = full / (float(n * n) * tileSize);
  m.offset = 2.0 * (t * tileSize + (0.5 * full - t - 0.5) / float(n) + 0.5) / (float(n) * tileSize) - 1.0;
  m.lo = 2.0 * t / float(n) - 1.0;
  m.hi = 2.0 * (t + 1.0) / float(n) - 1.0;
  return m;
}

// Maps the full-resolution clip position into the tile's block and clips it there.
vec4 toTile(vec4 clip, TileMap m) {
  vec4 tiled = vec4(m.scale * clip.xy + m.offset * clip.w, clip.z, clip.w);
  gl_ClipDistance[0] = tiled.x - m.lo.x * tiled.w;
  gl_ClipDistance[1] = m.hi.x * tiled.w - tiled.x;
  gl_ClipDistance[2] = tiled.y - m.lo.y * tiled.w;
  gl_ClipDistance[3] = m.hi.y * tiled.w - tiled.y;
  return tiled;
}

// True when every surface under the target-NDC rectangle lies in front of culling depth `nearDepth`
// (or there is none): the deepest over at most 2 x 2 texels of the pyramid level whose texels are at
// least as large as the rectangle.
bool surfacesInFront(vec4 rect, float nearDepth) {
  vec2 size = vec2(textureSize(surfaceDepthPyramid, 0));
  vec2 lo = clamp((rect.xy * 0.5 + 0.5) * size, vec2(0.0), size - 1.0);
  vec2 hi = clamp((rect.zw * 0.5 + 0.5) * size, vec2(0.0), size - 1.0);
  int top = textureQueryLevels(surfaceDepthPyramid) - 1;
  int level = clamp(int(ceil(log2(max(max(hi.x - lo.x, hi.y - lo.y), 1.0)))), 0, top);
  ivec2 last = textureSize(surfaceDepthPyramid, level) - 1;
  ivec2 a = min(ivec2(lo) >> level, last), b = min(ivec2(hi) >> level, last);
  float deepest = 0.0;
  for (int y = a.y; y <= b.y; ++y)
    for (int x = a.x; x <= b.x; ++x) deepest = max(deepest, texelFetch(surfaceDepthPyramid, ivec2(x, y), level).r);
  return deepest < nearDepth;
}

// The octagon's corners in triangle-strip order (a zigzag across the convex polygon).
const uint kOctagonStrip[8] = uint[](0u, 1u, 7u, 2u, 6u, 3u, 5u, 4u);

// A corner of the strip of the NDC octagon bounding the sphere (its rectangle with the corners cut by
// the diagonal tangents), at the volumeDepth of its far side (the depth test passes where the
// surface is not behind the sphere). The camera inside or beside the sphere: the whole viewport (in
// unsorted draws; sorted ones draw such a light as an icosahedron, crossingCorner).
// Nothing drawn (a degenerate rectangle) for a sphere wholly behind the eye, or one that every
// surface under its rectangle hides.
vec4 culledCorner(float radius, TileMap tile) {
  const vec4 nothing = vec4(0.0, 0.0, 0.0, 1.0);
  float r = radius * (1.0 + kCullingMargin);
  vec2 wRange = sphereClipWRange(frame.viewProjection, lightPosition, r);
  if (wRange.y <= 0.0) return nothing;
  vec4 bounds, diagonals;
  if (!projectedSphereBounds(frame.viewProjection, lightPosition, r, bounds, diagonals)) {
    bounds = vec4(-1.0, -1.0, 1.0, 1.0);
    diagonals = vec4(-2.0, -2.0, 2.0, 2.0);
  }
  bounds = clamp(bounds, -1.0, 1.0);  // also keeps far-off polygons away from the rasterizer's guard band
  vec4 inTile = clamp(vec4(tile.scale, tile.scale) * bounds + vec4(tile.offset, tile.offset), tile.lo.xyxy, tile.hi.xyxy);
  float nearDepth = cullingDepth(wRange.x * (1.0 - kCullingMargin), pass.cullingDepthScale);
  if (surfacesInFront(inTile, nearDepth)) return nothing;
  float farDepth = volumeDepth(wRange.y * (1.0 + kCullingMargin), frame.sceneScale.w);
  return vec4(octagonCorner(bounds, diagonals, kOctagonStrip[gl_VertexID]), farDepth, 1.0);
}

// A corner of the icosahedron whose faces lie at least `radius` (widened) from the light, at its own
// volumeDepth (clip z = nearW: depth nearW / w, clipped where w < nearW, in front of every surface).
// Front faces are culled (VolumeCulling::drawSorted): each pixel keeps the far side.
vec4 crossingCorner(float radius) {
  float r = radius * (1.0 + kCullingMargin) / kIcosahedronInradius;
  vec4 clip = frame.viewProjection * vec4(lightPosition + r * icosahedronCorner(uint(gl_VertexID)), 1.0);
  clip.z = frame.sceneScale.w;
  return clip;
}

void main() {
#ifdef LGH_SORTED_LIGHTS
  uint index = sortedLightIndex & ~kCrossingVolume;
  bool crossing = (sortedLightIndex & kCrossingVolume) != 0u;
#else
  const bool crossing = false;
  uint index = pass.instanceOffset + uint(gl_InstanceID);
#endif
#ifdef LGH_S0_INPUT
  ShadedLight l = decodeInputLight(lights[index]);
  lightId = kSlotS0 | (index + pass.boundLightOffset);
  lightVariance = vec3(0.0);
#else
  ShadedLight l = decodeGridLight(lights[index]);
  lightId = index;
  lightVariance = max(lights[index].variance, vec3(0.0));
#endif
  lightPosition = l.position;
  lightIntensity = l.intensity * pass.contributionScale;
  lightLobe = vec4(l.meanNormal, l.omniFraction);
  float R = levelRadius(pass.alpha, pass.topCellSize, l.level, pass.levels);
  uint role = pass.bruteForce != 0u ? kRoleOnly : levelRole(l.level, pass.firstLevel, pass.levels);
  lightBlend = vec2(R, float(role));

  TileMap tile = tileOf(index, l.level);
  vec4 clip;
  if (pass.volumeShape == kVolumeFullScreen)
    clip = fullScreenCorner();
  else if (pass.volumeShape == kVolumeCube)
    clip = cubeCorner(2.0 * R);
  else if (crossing)
    clip = crossingCorner(2.0 * R);
  else
    clip = culledCorner(2.0 * R, tile);
  gl_Position = toTile(clip, tile);
}
