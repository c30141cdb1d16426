#pragma once

// The shading model shared by every light of every level (docs/design.md §4), without the surface's
// rho/pi and without the blending weight: callers multiply those in.

#include <glm/vec3.hpp>

namespace lgh {

// Emission lobe F(u) of a light or cluster, u the unit direction from the light to the receiver:
//
//   F(u) = max(0, m·u) + (1 - |m| - o) / 4 + o,   clamped >= 0,
//
// with m the luminance-weighted mean normal and o the luminance-weighted share of omni lights.
//
// Why this form: a cosine emitter of peak intensity I emits the flux pi I, an omni light of
// intensity I emits 4 pi I, so a cluster of total intensity I, a share o of it omni, emits
// pi I (1 - o) + 4 pi I o = pi I (1 + 3o). Over the sphere, max(0, m·u) integrates to pi |m| and a
// constant c to 4 pi c, so the constant part (1 - |m| - o)/4 + o gives
//   pi |m| + pi (1 - |m| - o) + 4 pi o = pi (1 + 3o)
// for every |m|: the lobe conserves the cluster's flux however its normals are spread. (Our first
// design wrote (1 - |m|)/2 for the constant; that would double the flux of a cluster whose normals
// cancel, |m| = 0, which emits pi I but would get 2 pi I: docs/design.md §11.) The directional part keeps the cluster's
// net orientation; the rest, which the normals cancelled, is spread evenly. Special cases: one VPL (|m| = 1, o = 0)
// gives max(0, n·u) exactly; omni lights (m = 0, o = 1) give 1. Since |m| <= 1 - o for any cluster (hierarchy.h), the
// constant part is >= 0; the clamp guards rounding and out-of-range input only.
double emissionLobe(const glm::dvec3& meanNormal, double omniFraction, const glm::dvec3& u);

// Unshadowed contribution of one light at point x with unit normal *nx:
//
//   I * max(0, nx·w) * F(-w) / max(d², dc², kMinDistanceSq),   w = (p - x) / d,
//
// nx == nullptr means no surface (a point in the volume): the cosine is 1. dc is the clamp distance
// that keeps 1/d² finite near a light. When d == 0 the direction is undefined; w = nx (or +z without
// a surface) stands in, so nothing divides by zero and the result is never NaN.
glm::dvec3 lightContribution(const glm::dvec3& lightPos, const glm::dvec3& intensity, const glm::dvec3& meanNormal,
                             double omniFraction, const glm::dvec3& x, const glm::dvec3* nx, double clampDistance);

// Floor of the squared distance in lightContribution, in scene units²: with clampDistance = 0 it
// keeps a light at (or within 1e-12 of) the shading point finite instead of infinite. It is far
// below any meaningful scene scale, so it never changes a result that was finite before.
constexpr double kMinDistanceSq = 1e-24;

}  // namespace lgh
