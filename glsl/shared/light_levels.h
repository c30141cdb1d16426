// What the light pass and the shadow rays both need to know about a light of some level, written once
// for C++ and GLSL (see gpu_prelude.h): the level's blending radius R_l, its blending role, a light
// decoded from its storage form (S0 or grid light), and the screen-space bound of its light volume.
// lgh/blending.h and lgh/grid.h are the double-precision references; tests/render/light_levels_test.cpp
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
  uint level;          // 0 for S0
  vec3 meanNormal;     // |m| <= 1
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

// Screen-space bound of the sphere (centre c, radius r) under any projective matrix m (clip = m x):
// the NDC rectangle (xmin, ymin, xmax, ymax) inside which every point of the sphere projects. The
// planes clip.x = t clip.w are tangent to the sphere where (row0.c - t row3.c)^2 = r^2 |row0 - t row3|^2,
// a quadratic in t whose roots are the sphere's extent in NDC x (y alike). Only the rows x, y and w
// are read, so the depth convention (OpenGL, zero-to-one, reversed) does not matter. Returns false
// when the sphere reaches the plane w = 0 (the camera is inside it or beside it): then no finite
// rectangle bounds it and the caller covers the viewport.
GPU_FUNC bool projectedSphereBounds(mat4 m, vec3 c, float r, GPU_OUT(vec4) ndcBounds) {
  vec3 nx = vec3(m[0][0], m[1][0], m[2][0]), ny = vec3(m[0][1], m[1][1], m[2][1]), nw = vec3(m[0][3], m[1][3], m[2][3]);
  float ax = dot(nx, c) + m[3][0], ay = dot(ny, c) + m[3][1], aw = dot(nw, c) + m[3][3];
  float r2 = r * r;
  float a = aw * aw - r2 * dot(nw, nw);
  if (aw <= 0.0f || a <= 0.0f) return false;
  float xlo = 0.0f, xhi = 0.0f, ylo = 0.0f, yhi = 0.0f;
  bool x = orderedRoots(a, ax * aw - r2 * dot(nx, nw), ax * ax - r2 * dot(nx, nx), xlo, xhi);
  bool y = orderedRoots(a, ay * aw - r2 * dot(ny, nw), ay * ay - r2 * dot(ny, ny), ylo, yhi);
  if (!x || !y) return false;
  ndcBounds = vec4(xlo, ylo, xhi, yhi);
  return true;
}

// The sphere's extent along clip w, the depth the light pass tests against: w = row3 . (x, 1) is the
// distance in front of the camera's eye plane (times |row3.xyz|, 1 for perspective matrices).
GPU_FUNC vec2 sphereClipWRange(mat4 m, vec3 c, float r) {
  vec3 nw = vec3(m[0][3], m[1][3], m[2][3]);
  float aw = dot(nw, c) + m[3][3];
  float extent = r * sqrt(dot(nw, nw));
  return vec2(aw - extent, aw + extent);
}

// Depth stored for the light pass's culling test: clip w mapped monotonically onto [0, 1) so that
// any positive w fits a depth buffer; `scale` (about the scene's size) spreads typical depths over
// the range. w <= 0 (behind the eye) maps to 0.
GPU_FUNC float cullingDepth(float w, float scale) {
  return w > 0.0f ? w / (w + scale) : 0.0f;
}

GPU_NAMESPACE_END
#endif
