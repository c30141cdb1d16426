#pragma once

// The input lights S0 of the hierarchy and the one scalar the whole library ranks them by.

#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace lgh {

// A point light as the renderer hands it over: a glTF point light, an emitter sample, or a VPL.
// `intensity` is RGB in W/sr. An oriented (cosine) emitter, which every VPL is, radiates
// I * max(0, n·u) in direction u; `intensity` is then its peak intensity I = Phi / pi.
// `normal` is that emitter's unit normal, or exactly zero for an omni light (I in every direction).
struct Light {
  glm::vec3 position;
  glm::vec3 intensity;
  glm::vec3 normal{0.0f};
};

// Rec. 709 luminance. The hierarchy weights positions, normals and variances by it ("importance"),
// so a grid light sits where most of the visible light is, not where most of the lights are.
inline double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// A light's emission direction in double precision: its normal rescaled to unit length (a float
// normal is only unit to ~1e-7, and cluster normals must stay within |m| <= 1), or zero for omni.
glm::dvec3 unitNormal(const Light& light);

// 1 for an omni light, 0 for an oriented one: a single light's share of omni emission.
inline double omniFraction(const Light& light) { return light.normal == glm::vec3(0.0f) ? 1.0 : 0.0; }

// Returns "" when every light is usable, else a message naming the first bad light and why.
// Rejected: a non-finite position, intensity or normal; a negative intensity channel; a normal that
// is neither zero nor unit length (within 1e-3: the emission lobe's flux bookkeeping assumes |n| = 1).
// Lights of zero intensity are legal: they contribute nothing and do not shape the grid.
std::string validateLights(const std::vector<Light>& lights);

// validateLights for the builders: throws std::invalid_argument carrying its message.
void requireValidLights(const std::vector<Light>& lights);

}  // namespace lgh
