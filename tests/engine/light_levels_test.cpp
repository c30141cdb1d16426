// The functions light_volume.vert and shadow_rays.comp share with C++ (glsl/shared/light_levels.h),
// compiled here as C++: roles and radii against the double-precision library (lgh/blending.h), light
// decoding against the stored fields, and the light volume's screen bound against projected points of
// the sphere (it must contain all of them, and touch them: conservative and tight).
#include "shared/light_levels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <random>
#include <utility>

#include "lgh/blending.h"

namespace lgh {
namespace {

TEST(LightLevels, RolesAreTheLibrarysRoles) {
  EXPECT_EQ(gpu::kRoleFinest, unsigned(LevelRole::Finest));
  EXPECT_EQ(gpu::kRoleMiddle, unsigned(LevelRole::Middle));
  EXPECT_EQ(gpu::kRoleTop, unsigned(LevelRole::Top));
  EXPECT_EQ(gpu::kRoleOnly, unsigned(LevelRole::Only));
  for (int levels = 0; levels <= 8; ++levels)
    for (int first = 0; first <= std::min(levels, 1); ++first)
      for (int level = first; level <= levels; ++level)
        EXPECT_EQ(gpu::levelRole(unsigned(level), unsigned(first), unsigned(levels)),
                  unsigned(levelRole(level, first, levels)))
            << "level " << level << " of " << first << ".." << levels;
}

TEST(LightLevels, RadiusIsAlphaTimesCellSize) {
  const float alpha = 1.5f, H = 12.0f;
  for (unsigned levels = 1; levels <= 11; ++levels)
    for (unsigned level = 0; level <= levels; ++level)
      EXPECT_FLOAT_EQ(gpu::levelRadius(alpha, H, level, levels),
                      float(alpha * std::ldexp(double(H), int(level) - int(levels))));
  // R_{l+1} = 2 R_l: the blending bands of neighbouring levels meet.
  EXPECT_FLOAT_EQ(gpu::levelRadius(1.0f, 1.0f, 3, 5), 2.0f * gpu::levelRadius(1.0f, 1.0f, 2, 5));
}

TEST(LightLevels, DecodesInputAndGridLights) {
  gpu::GpuLight vpl{glm::vec3(1, 2, 3), gpu::octEncode(glm::normalize(glm::vec3(0, 1, 1))), glm::vec3(4, 5, 6),
                    gpu::kLightOriented};
  const gpu::ShadedLight s = gpu::decodeInputLight(vpl);
  EXPECT_EQ(s.position, vpl.position);
  EXPECT_EQ(s.intensity, vpl.intensity);
  EXPECT_NEAR(glm::distance(s.meanNormal, glm::normalize(glm::vec3(0, 1, 1))), 0.0f, 1e-3f);
  EXPECT_EQ(s.omniFraction, 0.0f);
  EXPECT_EQ(s.level, 0u);
  vpl.flags = 0;  // omni: no lobe
  EXPECT_EQ(gpu::decodeInputLight(vpl).omniFraction, 1.0f);
  EXPECT_EQ(gpu::decodeInputLight(vpl).meanNormal, glm::vec3(0.0f));

  gpu::GpuGridLight g{};
  g.position = glm::vec3(-1, 0, 2);
  g.level = 3;
  g.intensity = glm::vec3(7, 8, 9);
  g.omniFraction = 0.25f;
  g.meanNormal = glm::vec3(0, 0.5f, 0);
  const gpu::ShadedLight t = gpu::decodeGridLight(g);
  EXPECT_EQ(t.position, g.position);
  EXPECT_EQ(t.level, 3u);
  EXPECT_EQ(t.intensity, g.intensity);
  EXPECT_EQ(t.omniFraction, 0.25f);
  EXPECT_EQ(t.meanNormal, g.meanNormal);
}

// Random cameras (with off-centre frusta) and spheres in front of them: every point of the sphere
// projects inside the bound, and points come within 2% of its size of each of its four edges.
TEST(LightLevels, SphereBoundContainsAndTouchesTheProjectedSphere) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int bounded = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const glm::vec3 eye(3 * u(rng), 3 * u(rng), 3 * u(rng));
    const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(u(rng), u(rng), -1.0f), glm::vec3(0, 1, 0));
    const float n = 0.1f, s = 0.1f * (1.2f + u(rng));
    const glm::mat4 projection = glm::frustum(-s + 0.03f * u(rng), s, -s * 0.6f, s * 0.6f + 0.02f * u(rng), n, 100.0f);
    const glm::mat4 m = projection * view;
    const glm::vec3 c =
        eye + glm::vec3(glm::inverse(view) * glm::vec4(2 * u(rng), 2 * u(rng), -3.0f + 2.5f * u(rng), 0.0f));
    const float r = 0.05f + 1.5f * std::abs(u(rng));
    glm::vec4 bounds(0.0f), diagonals(0.0f);
    const glm::vec2 w = gpu::sphereClipWRange(m, c, r);
    const bool finite = gpu::projectedSphereBounds(m, c, r, bounds, diagonals);
    // No finite bound exactly when the sphere reaches the eye plane.
    EXPECT_EQ(finite, w.x > 0.0f) << "trial " << trial;
    if (!finite) continue;
    ++bounded;
    glm::vec4 reached(1e9f, 1e9f, -1e9f, -1e9f);
    for (int i = 0; i < 4000; ++i) {
      glm::vec3 d(u(rng), u(rng), u(rng));
      if (glm::length(d) < 1e-3f) continue;
      const glm::vec4 clip = m * glm::vec4(c + r * glm::normalize(d), 1.0f);
      EXPECT_GE(clip.w, w.x * (1 - 1e-4f) - 1e-5f);
      EXPECT_LE(clip.w, w.y * (1 + 1e-4f) + 1e-5f);
      const glm::vec2 ndc = glm::vec2(clip) / clip.w;
      const float tolerance = 1e-4f * (1.0f + glm::length(ndc));
      ASSERT_GE(ndc.x, bounds.x - tolerance) << "trial " << trial;
      ASSERT_GE(ndc.y, bounds.y - tolerance) << "trial " << trial;
      ASSERT_LE(ndc.x, bounds.z + tolerance) << "trial " << trial;
      ASSERT_LE(ndc.y, bounds.w + tolerance) << "trial " << trial;
      // Inside the octagon: the diagonal ranges hold x + y and x - y too.
      ASSERT_GE(ndc.x + ndc.y, diagonals.x - 2 * tolerance) << "trial " << trial;
      ASSERT_LE(ndc.x + ndc.y, diagonals.z + 2 * tolerance) << "trial " << trial;
      ASSERT_GE(ndc.x - ndc.y, diagonals.y - 2 * tolerance) << "trial " << trial;
      ASSERT_LE(ndc.x - ndc.y, diagonals.w + 2 * tolerance) << "trial " << trial;
      reached = glm::vec4(glm::min(glm::vec2(reached), ndc), glm::max(glm::vec2(reached.z, reached.w), ndc));
    }
    const float size = std::max(bounds.z - bounds.x, bounds.w - bounds.y);
    // Tightness where sampling can show it: a sphere almost touching the eye plane projects to a huge
    // rectangle whose extremes 4000 random points do not come near.
    if (size > 20.0f) continue;
    EXPECT_LT(reached.x - bounds.x, 2e-2f * size) << "trial " << trial;
    EXPECT_LT(reached.y - bounds.y, 2e-2f * size) << "trial " << trial;
    EXPECT_LT(bounds.z - reached.z, 2e-2f * size) << "trial " << trial;
    EXPECT_LT(bounds.w - reached.w, 2e-2f * size) << "trial " << trial;
  }
  EXPECT_GT(bounded, 150);
}

// The octagon's corners lie on its boundary: inside the rectangle and the diagonal ranges, each
// corner on at least two of the eight lines, in counter-clockwise order (a convex polygon).
TEST(LightLevels, OctagonCornersBoundTheSameRegion) {
  const glm::mat4 m = glm::perspective(1.0f, 1.6f, 0.1f, 100.0f);
  for (float x : {-2.0f, 0.0f, 1.5f})
    for (float r : {0.3f, 1.0f}) {
      glm::vec4 box, diagonals;
      ASSERT_TRUE(gpu::projectedSphereBounds(m, glm::vec3(x, 0.5f, -5.0f), r, box, diagonals));
      float area = 0;
      for (unsigned k = 0; k < 8; ++k) {
        const glm::vec2 p = gpu::octagonCorner(box, diagonals, k), q = gpu::octagonCorner(box, diagonals, (k + 1) % 8);
        EXPECT_GE(p.x, box.x - 1e-6f);
        EXPECT_LE(p.x, box.z + 1e-6f);
        EXPECT_GE(p.x + p.y, diagonals.x - 1e-5f);
        EXPECT_LE(p.x + p.y, diagonals.z + 1e-5f);
        EXPECT_GE(p.x - p.y, diagonals.y - 1e-5f);
        EXPECT_LE(p.x - p.y, diagonals.w + 1e-5f);
        area += p.x * q.y - q.x * p.y;
      }
      const float rectangle = (box.z - box.x) * (box.w - box.y);
      EXPECT_GT(0.5f * area, 0.75f * rectangle);  // at least the inscribed ellipse's pi/4 of it
      EXPECT_LT(0.5f * area, 0.90f * rectangle);  // the corners are cut
    }
}

TEST(LightLevels, CullingDepthIsMonotonicInW) {
  float last = -1.0f;
  for (float w = -1.0f; w < 1e6f; w = w < 0.0f ? 0.0f : w * 1.5f + 1e-4f) {
    const float d = gpu::cullingDepth(w, 30.0f);
    EXPECT_GE(d, 0.0f);
    EXPECT_LT(d, 1.0f);
    EXPECT_GE(d, last);
    last = d;
  }
}

// The depth culled volumes are tested with is reversed (nearer is larger) and, being nearW / w, affine
// in screen space: over a triangle in front of the camera, the depth at a point equals the screen-space
// interpolation of its corners' depths, as the rasterizer computes it.
TEST(LightLevels, VolumeDepthIsReversedAndAffineOnScreen) {
  const float nearW = 0.05f;
  EXPECT_EQ(gpu::volumeDepth(-1.0f, nearW), 1.0f);
  EXPECT_EQ(gpu::volumeDepth(0.01f, nearW), 1.0f);
  EXPECT_FLOAT_EQ(gpu::volumeDepth(0.5f, nearW), 0.1f);
  const glm::mat4 m = glm::perspective(1.0f, 1.6f, nearW, 100.0f);
  const glm::vec3 corners[3] = {{-3.0f, 1.0f, -2.0f}, {4.0f, -1.0f, -9.0f}, {0.5f, 2.0f, -40.0f}};
  glm::vec2 screen[3];
  float depth[3];
  for (int k = 0; k < 3; ++k) {
    const glm::vec4 clip = m * glm::vec4(corners[k], 1.0f);
    screen[k] = glm::vec2(clip) / clip.w;
    depth[k] = gpu::volumeDepth(gpu::clipW(m, corners[k]), nearW);
  }
  for (glm::vec3 b : {glm::vec3(0.2f, 0.3f, 0.5f), glm::vec3(0.7f, 0.1f, 0.2f), glm::vec3(0.05f, 0.05f, 0.9f)}) {
    // The point of the triangle that projects to screen-space barycentrics b.
    const glm::vec3 perspective =
        b / glm::vec3(gpu::clipW(m, corners[0]), gpu::clipW(m, corners[1]), gpu::clipW(m, corners[2]));
    const glm::vec3 w3 = perspective / (perspective.x + perspective.y + perspective.z);
    const glm::vec3 point = w3.x * corners[0] + w3.y * corners[1] + w3.z * corners[2];
    const glm::vec4 clip = m * glm::vec4(point, 1.0f);
    const glm::vec2 onScreen = b.x * screen[0] + b.y * screen[1] + b.z * screen[2];
    EXPECT_NEAR(clip.x / clip.w, onScreen.x, 1e-5f);
    EXPECT_NEAR(clip.y / clip.w, onScreen.y, 1e-5f);
    const float interpolated = b.x * depth[0] + b.y * depth[1] + b.z * depth[2];
    EXPECT_NEAR(gpu::volumeDepth(clip.w, nearW), interpolated, 1e-5f * interpolated);
  }
}

// The crossing spheres' icosahedron: a closed surface (every edge shared by two faces, once each way),
// its faces counter-clockwise seen from outside, each at least kIcosahedronInradius from the centre, so
// that scaled by r / kIcosahedronInradius it contains the sphere of radius r.
TEST(LightLevels, IcosahedronEnclosesTheSphere) {
  std::map<std::pair<int, int>, int> edges;
  auto key = [](glm::vec3 v) {
    return int(std::lround(v.x * 8 + 64)) * 1000000 + int(std::lround(v.y * 8 + 64)) * 1000 +
           int(std::lround(v.z * 8 + 64));
  };
  float nearest = 1e30f;
  for (unsigned f = 0; f < gpu::kCrossingVolumeVertices / 3; ++f) {
    const glm::vec3 a = gpu::icosahedronCorner(3 * f), b = gpu::icosahedronCorner(3 * f + 1),
                    c = gpu::icosahedronCorner(3 * f + 2);
    for (const glm::vec3& v : {a, b, c}) EXPECT_NEAR(glm::length(v), 1.9021130f, 1e-5f);
    EXPECT_NEAR(glm::length(b - a), 2.0f, 1e-5f);
    EXPECT_NEAR(glm::length(c - b), 2.0f, 1e-5f);
    EXPECT_NEAR(glm::length(a - c), 2.0f, 1e-5f);
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    const float distance = glm::dot(n, a);
    EXPECT_GT(distance, 0.0f) << "face " << f << " faces inwards";
    nearest = std::min(nearest, distance);
    const glm::vec3 corners[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) ++edges[{key(corners[e]), key(corners[(e + 1) % 3])}];
  }
  EXPECT_GE(nearest, gpu::kIcosahedronInradius);
  EXPECT_LT(nearest, gpu::kIcosahedronInradius * 1.0001f);
  EXPECT_EQ(edges.size(), 60u);
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
  }
}

}  // namespace
}  // namespace lgh
