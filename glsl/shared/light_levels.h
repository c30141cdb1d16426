// What the light pass and the shadow rays both need to know about a light of some level, written once
// for C++ and GLSL (see gpu_prelude.h): the level's blending radius R_l, its blending role, a light
// decoded from its storage form (S0 or grid light), and the screen-space bound of its light volume.
// lgh/blending.h and lgh/grid.h are the double-precision references; tests/engine/light_levels_test.cpp
// holds these to them and to brute-force projections.
#ifndef LGH_LIGHT_LEVELS_H
#define LGH_LIGHT_LEVELS_H
#include "shared/gpu_prelude.h"
#include "shared/lgh_types.h"
#include "shared/octahedral.h"

GPU_NAMESPACE_BEGIN

// Blending roles (lgh::LevelRole, in the same order).
GPU_CONST uint kRoleFinest = 0u;
GPU_CONST uint kRoleMiddle = 1u;
GPU_CONST uint kRoleTop = 2u;
GPU_CONST uint kRoleOnly = 3u;

// The role of `level` when levels firstLevel..levels are blended (lgh::levelRole).
GPU_FUNC uint levelRole(uint level, uint firstLevel, uint levels) {
  if (firstLevel == levels) return kRoleOnly;
  if (level == firstLevel) return kRoleFinest;
  if (level == levels) return kRoleTop;
  return kRoleMiddle;
}

// R_l = alpha h_l with h_l = H 2^(l - L) (lgh::Grid::radius); S0 (l = 0) gets h_0 = h_1 / 2.
GPU_FUNC float levelRadius(float alpha, float topCellSize, uint level, uint levels) {
  return alpha * topCellSize * exp2(float(int(level) - int(levels)));
}

// A light as shading reads it, whichever buffer it came from.
GPU_STRUCT(ShadedLight) {
  vec3 position;
  float omniFraction;  // 1: omni (a punctual light), 0: a pure cosine lobe around meanNormal
  vec3 intensity;
  uint level;       // 0 for S0
  vec3 meanNormal;  // |m| <= 1
  float pad;
};

GPU_FUNC ShadedLight decodeInputLight(GpuLight l) {
  ShadedLight s;
  s.position = l.position;
  s.intensity = l.intensity;
  bool oriented = (l.flags & kLightOriented) != 0u;
  s.meanNormal = oriented ? octDecode(l.normalOct) : vec3(0.0f);
  s.omniFraction = oriented ? 0.0f : 1.0f;
  s.level = 0u;
  s.pad = 0.0f;
  return s;
}

GPU_FUNC ShadedLight decodeGridLight(GpuGridLight g) {
  ShadedLight s;
  s.position = g.position;
  s.intensity = g.intensity;
  s.meanNormal = g.meanNormal;
  s.omniFraction = g.omniFraction;
  s.level = g.level;
  s.pad = 0.0f;
  return s;
}

// The two roots t of a*t^2 - 2*b*t + c = 0 in order, false when there are none.
GPU_FUNC bool orderedRoots(float a, float b, float c, GPU_OUT(float) lo, GPU_OUT(float) hi) {
  float discriminant = b * b - a * c;
  if (a <= 0.0f || discriminant < 0.0f) return false;
  float root = sqrt(discriminant);
  lo = (b - root) / a;
  hi = (b + root) / a;
  return true;
}

// The range of clip.row / clip.w over the sphere (centre c, radius r) for one row of a projective
// matrix (n, a: row . (c, 1)) and its w row (nw, aw): the planes clip.row = t clip.w tangent to the
// sphere, where (a - t aw)^2 = r^2 |n - t nw|^2, a quadratic in t. False when the sphere reaches the
// plane w = 0 (no finite range).
GPU_FUNC bool sphereRatioRange(vec3 n, float a, vec3 nw, float aw, float r, GPU_OUT(float) lo, GPU_OUT(float) hi) {
  float r2 = r * r;
  float quadratic = aw * aw - r2 * dot(nw, nw);
  if (aw <= 0.0f || quadratic <= 0.0f) return false;
  return orderedRoots(quadratic, a * aw - r2 * dot(n, nw), a * a - r2 * dot(n, n), lo, hi);
}

// Screen-space bound of the sphere (centre c, radius r) under any projective matrix m (clip = m x):
// the NDC rectangle (xmin, ymin, xmax, ymax) inside which every point of the sphere projects, and in
// `diagonals` the ranges of x + y and x - y over it (umin, vmin, umax, vmax), which cut the rectangle's
// corners into an octagon. Only the rows x, y and w are read, so the depth convention (OpenGL,
// zero-to-one, reversed) does not matter. Returns false when the sphere reaches the plane w = 0 (the
// camera is inside it or beside it): then no finite polygon bounds it and the caller covers the viewport.
GPU_FUNC bool projectedSphereBounds(mat4 m, vec3 c, float r, GPU_OUT(vec4) ndcBounds, GPU_OUT(vec4) diagonals) {
  vec3 nx = vec3(m[0][0], m[1][0], m[2][0]), ny = vec3(m[0][1], m[1][1], m[2][1]), nw = vec3(m[0][3], m[1][3], m[2][3]);
  float ax = dot(nx, c) + m[3][0], ay = dot(ny, c) + m[3][1], aw = dot(nw, c) + m[3][3];
  float xlo = 0.0f, xhi = 0.0f, ylo = 0.0f, yhi = 0.0f, ulo = 0.0f, uhi = 0.0f, vlo = 0.0f, vhi = 0.0f;
  if (!sphereRatioRange(nx, ax, nw, aw, r, xlo, xhi) || !sphereRatioRange(ny, ay, nw, aw, r, ylo, yhi) ||
      !sphereRatioRange(nx + ny, ax + ay, nw, aw, r, ulo, uhi) ||
      !sphereRatioRange(nx - ny, ax - ay, nw, aw, r, vlo, vhi))
    return false;
  ndcBounds = vec4(xlo, ylo, xhi, yhi);
  diagonals = vec4(ulo, vlo, uhi, vhi);
  return true;
}

// Corner k (0..7, counter-clockwise from the bottom edge's left end) of the octagon where the
// rectangle meets the diagonal bounds; corners the diagonals do not cut collapse onto the rectangle's.
GPU_FUNC vec2 octagonCorner(vec4 box, vec4 diagonals, uint k) {
  float xlo = box.x, ylo = box.y, xhi = box.z, yhi = box.w;
  float ulo = diagonals.x, vlo = diagonals.y, uhi = diagonals.z, vhi = diagonals.w;
  vec2 p;
  if (k == 0u)
    p = vec2(ulo - ylo, ylo);
  else if (k == 1u)
    p = vec2(vhi + ylo, ylo);
  else if (k == 2u)
    p = vec2(xhi, xhi - vhi);
  else if (k == 3u)
    p = vec2(xhi, uhi - xhi);
  else if (k == 4u)
    p = vec2(uhi - yhi, yhi);
  else if (k == 5u)
    p = vec2(vlo + yhi, yhi);
  else if (k == 6u)
    p = vec2(xlo, xlo - vlo);
  else
    p = vec2(xlo, ulo - xlo);
  return clamp(p, vec2(xlo, ylo), vec2(xhi, yhi));
}

// The sphere's extent along clip w, the depth the light pass tests against: w = row3 . (x, 1) is the
// distance in front of the camera's eye plane (times |row3.xyz|, 1 for perspective matrices).
GPU_FUNC vec2 sphereClipWRange(mat4 m, vec3 c, float r) {
  vec3 nw = vec3(m[0][3], m[1][3], m[2][3]);
  float aw = dot(nw, c) + m[3][3];
  float extent = r * sqrt(dot(nw, nw));
  return vec2(aw - extent, aw + extent);
}

// Clip w of a point: its distance in front of the eye plane (times |row3.xyz|).
GPU_FUNC float clipW(mat4 m, vec3 x) { return m[0][3] * x.x + m[1][3] * x.y + m[2][3] * x.z + m[3][3]; }

// Depth stored for the light pass's culling test: clip w mapped monotonically onto [0, 1) so that
// any positive w fits a depth buffer; `scale` (about the scene's size) spreads typical depths over
// the range. w <= 0 (behind the eye) maps to 0.
GPU_FUNC float cullingDepth(float w, float scale) { return w > 0.0f ? w / (w + scale) : 0.0f; }

// Inverse of cullingDepth for 0 <= depth < 1.
GPU_FUNC float cullingDepthW(float depth, float scale) { return scale * depth / (1.0f - depth); }

// The depth buffer the culled volumes are tested against holds volumeDepth, not cullingDepth: nearW / w,
// reversed like the G-buffer's (1 at the near plane, towards 0 far away). 1 / w is affine in screen
// space, so a planar polygon drawn with clip z = nearW and GL_ZERO_TO_ONE carries exactly this depth at
// every pixel (and is clipped at w = nearW): the faces of a polyhedron bound their far side per pixel,
// not just by one plane. Float keeps its relative precision at every distance. nearW: no surface is
// nearer (the camera's near plane); nearer or behind the eye clamps to 1.
GPU_FUNC float volumeDepth(float w, float nearW) { return w > nearW ? nearW / w : 1.0f; }

// A sphere that reaches the eye plane w = 0 (the camera inside it or beside it) has no finite screen
// bound (projectedSphereBounds fails). Its volume is then the back faces of a regular icosahedron
// around it, at volumeDepth: with the camera inside, every pixel sees one back face at the polyhedron's
// own far side, so only surfaces inside the polyhedron pass the depth test. Sorted draws flag such
// lights (light_slices.comp) in the index's top bit and draw them as kCrossingVolumeVertices triangle
// vertices.
GPU_CONST uint kCrossingVolume = 0x80000000u;
GPU_CONST uint kCrossingVolumeVertices = 60u;
// The icosahedron with vertices (0, +-1, +-phi) and their cyclic permutations has inradius
// phi^2 / sqrt(3) = 1.5115226...; scaled by r / kIcosahedronInradius its faces lie at least r from the
// centre (rounded down: slightly farther).
GPU_CONST float kIcosahedronInradius = 1.51152f;

// Vertex k (0..11) of that icosahedron: k = 6 a + 3 b + c is the c-th cyclic permutation of
// (0, -+1, -+phi) with the signs from a and b.
GPU_FUNC vec3 icosahedronVertex(uint k) {
  float a = (k / 6u) == 0u ? -1.0f : 1.0f;
  float b = ((k / 3u) % 2u) == 0u ? -1.6180340f : 1.6180340f;
  uint c = k % 3u;
  return c == 0u ? vec3(0.0f, a, b) : c == 1u ? vec3(a, b, 0.0f) : vec3(b, 0.0f, a);
}

// Corner i (0..59) of its 20 triangles, counter-clockwise seen from outside: the vertex indices
// packed four bits each, eight to a word.
GPU_FUNC vec3 icosahedronCorner(uint i) {
  uint w = i / 8u;
  uint word = w == 0u   ? 0x20170210u
              : w == 1u ? 0x17505606u
              : w == 2u ? 0x83137128u
              : w == 3u ? 0x73482642u
              : w == 4u ? 0x49b3893bu
              : w == 5u ? 0xa949846au
              : w == 6u ? 0xa57b5a65u
                        : 0x0000ab9bu;
  return icosahedronVertex((word >> (4u * (i % 8u))) & 15u);
}

// Depth slices for culling surfaces in front of a volume (LightVolumePass): `slices` slices of equal
// width in culling depth over [0, kSlicedDepth), the last one open-ended. A pixel's stencil holds the
// number of boundaries at or before its surface's depth; a light drawn with stencil reference
// sliceOf(its sphere's nearest depth) passes only where the surface is not in front of that boundary.
GPU_CONST float kSlicedDepth = 2.0f / 3.0f;  // cullingDepth(2 x scale): twice the scene's size
GPU_CONST uint kMaxCullingSlices = 255u;     // 8-bit stencil

// Boundary j (1 <= j < slices) between slices j - 1 and j.
GPU_FUNC float sliceBoundary(uint j, uint slices) { return float(j) * (kSlicedDepth / float(slices)); }

// The number of boundaries at or before `depth` (0 .. slices - 1); never more, whatever the rounding,
// so that comparing a light's slice with the pixel's stencil stays conservative.
GPU_FUNC uint sliceOf(float depth, uint slices) {
  float k = floor(depth * (float(slices) / kSlicedDepth));
  uint j = uint(clamp(k, 0.0f, float(slices - 1u)));
  if (j > 0u && sliceBoundary(j, slices) > depth) j -= 1u;
  return j;
}

GPU_NAMESPACE_END
#endif
