#include "render/scene/animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/scene/scene.h"

namespace lgh {
namespace {

glm::dquat toQuat(const glm::vec4& xyzw) { return glm::dquat(xyzw.w, xyzw.x, xyzw.y, xyzw.z); }
glm::vec4 toXyzw(const glm::dquat& q) { return glm::vec4(float(q.x), float(q.y), float(q.z), float(q.w)); }

glm::dquat normalized(const glm::dquat& q) {
  const double length = glm::length(q);
  return length > 0.0 && std::isfinite(length) ? q / length : glm::dquat(1.0, 0.0, 0.0, 0.0);
}

// glTF 2.0 Appendix C's slerp: along the shorter arc (b's sign flipped when the dot product is negative),
// linear where the two are too close for the sine's quotient.
glm::dquat slerp(const glm::dquat& a, glm::dquat b, double t) {
  double d = glm::dot(a, b);
  if (d < 0.0) {
    b = -b;
    d = -d;
  }
  if (d > 1.0 - 1e-9) return normalized(a * (1.0 - t) + b * t);
  const double angle = std::acos(d), s = std::sin(angle);
  return normalized(a * (std::sin((1.0 - t) * angle) / s) + b * (std::sin(t * angle) / s));
}

glm::vec3 faceNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  return length > 0.0 && std::isfinite(length) ? glm::vec3(n / length) : glm::vec3(0.0f, 1.0f, 0.0f);
}

glm::dmat4 localTransform(const RigNode& node) {
  if (node.hasMatrix) return node.matrix;
  return glm::translate(glm::dmat4(1.0), node.translation) * glm::mat4_cast(node.rotation) *
         glm::scale(glm::dmat4(1.0), node.scale);
}

}  // namespace

glm::vec4 sampleChannel(const AnimationChannel& c, double time) {
  const bool rotation = c.path == AnimationPath::Rotation;
  const bool cubic = c.interpolation == Interpolation::CubicSpline;
  const size_t n = c.times.size();
  // The value of key k (the middle of the three cubic-spline entries).
  const auto value = [&](size_t k) { return c.keys[cubic ? 3 * k + 1 : k]; };
  const auto finish = [&](const glm::vec4& v) { return rotation ? toXyzw(normalized(toQuat(v))) : v; };
  if (n == 0) return rotation ? glm::vec4(0, 0, 0, 1) : glm::vec4(0.0f);
  if (!(time > double(c.times.front()))) return finish(value(0));
  if (time >= double(c.times.back())) return finish(value(n - 1));
  // The interval [t_k, t_k+1) holding `time`.
  const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), time,
                                           [](double t, float key) { return t < double(key); }) -
                          c.times.begin()) -
                   1;
  const double t0 = c.times[k], t1 = c.times[k + 1], span = t1 - t0;
  const double u = (time - t0) / span;
  switch (c.interpolation) {
    case Interpolation::Step:
      return finish(value(k));
    case Interpolation::Linear:
      if (rotation) return toXyzw(slerp(normalized(toQuat(value(k))), normalized(toQuat(value(k + 1))), u));
      return glm::vec4(glm::mix(glm::dvec4(value(k)), glm::dvec4(value(k + 1)), u));
    case Interpolation::CubicSpline: {
      // p(u) = (2u^3 - 3u^2 + 1) v_k + span (u^3 - 2u^2 + u) b_k + (-2u^3 + 3u^2) v_k+1 + span (u^3 - u^2) a_k+1,
      // with b_k key k's out-tangent and a_k+1 key k+1's in-tangent.
      const double u2 = u * u, u3 = u2 * u;
      const glm::dvec4 v0(c.keys[3 * k + 1]), b0(c.keys[3 * k + 2]), v1(c.keys[3 * k + 4]), a1(c.keys[3 * k + 3]);
      const glm::dvec4 p =
          (2 * u3 - 3 * u2 + 1) * v0 + span * (u3 - 2 * u2 + u) * b0 + (-2 * u3 + 3 * u2) * v1 + span * (u3 - u2) * a1;
      return finish(glm::vec4(p));
    }
  }
  return finish(value(k));
}

std::vector<glm::dmat4> SceneAnimation::worldTransforms(double time) const {
  std::vector<RigNode> posed = nodes;
  for (const AnimationChannel& c : channels) {
    RigNode& node = posed[size_t(c.node)];
    const glm::vec4 v = sampleChannel(c, time);
    switch (c.path) {
      case AnimationPath::Translation:
        node.translation = glm::dvec3(v);
        break;
      case AnimationPath::Rotation:
        node.rotation = toQuat(v);
        break;
      case AnimationPath::Scale:
        node.scale = glm::dvec3(v);
        break;
    }
  }
  // Parents before children: the file's order need not be, so each node's chain is resolved on demand.
  std::vector<glm::dmat4> world(posed.size());
  std::vector<char> done(posed.size(), 0);
  std::vector<int> chain;
  for (size_t i = 0; i < posed.size(); ++i) {
    for (int j = int(i); j >= 0 && !done[size_t(j)]; j = posed[size_t(j)].parent) chain.push_back(j);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const RigNode& node = posed[size_t(*it)];
      world[size_t(*it)] = node.parent >= 0 ? world[size_t(node.parent)] * localTransform(node) : localTransform(node);
      done[size_t(*it)] = 1;
    }
    chain.clear();
  }
  return world;
}

bool lightPlacement(const glm::dmat4& world, const glm::dvec3& origin, glm::vec3& position, glm::vec3& direction) {
  const glm::dvec3 d = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
  const double length = glm::length(d);
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  position = glm::vec3(glm::dvec3(world[3]) - origin);
  direction = glm::vec3(d / length);
  return true;
}

bool cameraPlacement(const glm::dmat4& world, const glm::dvec3& origin, glm::vec3& position, glm::mat3& orientation) {
  glm::vec3 at, forward;
  if (!lightPlacement(world, origin, at, forward)) return false;
  // Gram-Schmidt from the view axis: node scale and shear must not skew the view, and right = up x back
  // keeps the basis right-handed even under a mirroring parent.
  const glm::dvec3 back = -glm::dvec3(forward);
  const glm::dvec3 axisY(world[1]);
  glm::dvec3 up = axisY - glm::dot(axisY, back) * back;
  if (!(glm::length(up) > 1e-12)) return false;
  up = glm::normalize(up);
  position = at;
  orientation = glm::mat3(glm::vec3(glm::cross(up, back)), glm::vec3(up), glm::vec3(back));
  return true;
}

void PoseChange::merge(const PoseChange& other) {
  geometry |= other.geometry;
  cameras |= other.cameras;
  for (size_t i : other.lights)
    if (std::find(lights.begin(), lights.end(), i) == lights.end()) lights.push_back(i);
}

PoseChange poseScene(Scene& scene, double time) {
  PoseChange change;
  const SceneAnimation& animation = scene.animation;
  if (animation.empty()) return change;
  const std::vector<glm::dmat4> world = animation.worldTransforms(time);
  for (const MovingPrimitive& p : animation.primitives) {
    const glm::dmat4& m = world[size_t(p.node)];
    const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(m));
    std::vector<glm::dvec3> posed(p.vertexCount);
    for (std::uint32_t v = 0; v < p.vertexCount; ++v) {
      posed[v] = glm::dvec3(m * glm::dvec4(glm::dvec3(p.positions[v]), 1.0));
      const glm::vec3 position(posed[v] - scene.origin);
      change.geometry |= position != scene.positions[p.firstVertex + v];
      scene.positions[p.firstVertex + v] = position;
    }
    for (std::uint32_t v = 0; v < p.vertexCount; ++v) {
      glm::vec3 n;
      if (p.normals.empty()) {  // flat: the vertex's triangle is the three vertices from a multiple of 3
        const std::uint32_t t = v / 3 * 3;
        n = faceNormal(posed[t], posed[t + 1], posed[t + 2]);
      } else {
        const glm::dvec3 transformed = normalMatrix * glm::dvec3(p.normals[v]);
        const double length = glm::length(transformed);
        n = length > 0.0 && std::isfinite(length) ? glm::vec3(transformed / length) : glm::vec3(0.0f, 1.0f, 0.0f);
      }
      change.geometry |= n != scene.normals[p.firstVertex + v];
      scene.normals[p.firstVertex + v] = n;
    }
  }
  for (size_t i = 0; i < scene.lights.size() && i < animation.lightNodes.size(); ++i) {
    if (!animation.carriesLight(i)) continue;
    const int node = animation.lightNodes[i];
    PunctualLight& light = scene.lights[i];
    const glm::vec3 position = light.position, direction = light.direction;
    if (lightPlacement(world[size_t(node)], scene.origin, light.position, light.direction) &&
        (light.position != position || light.direction != direction))
      change.lights.push_back(i);
  }
  for (size_t i = 0; i < scene.cameras.size() && i < animation.cameraNodes.size(); ++i) {
    const int node = animation.cameraNodes[i];
    if (!animation.moves(node)) continue;
    Camera& camera = scene.cameras[i];
    const glm::vec3 position = camera.position;
    const glm::mat3 orientation = camera.orientation;
    if (cameraPlacement(world[size_t(node)], scene.origin, camera.position, camera.orientation))
      change.cameras |= camera.position != position || camera.orientation != orientation;
  }
  return change;
}

}  // namespace lgh
