// frameBounds: the fallback camera when a scene names none (or the user asks for an overview).
#include <algorithm>
#include <cmath>

#include "render/scene/scene.h"

namespace lgh {

Camera frameBounds(const Bounds& bounds, float aspectRatio) {
  // An empty or degenerate box (no geometry, a single point, NaNs) still gets a usable camera:
  // centre the origin or the point, and frame a sphere of radius 1.
  glm::vec3 center(0.0f);
  float radius = 1.0f;
  if (!bounds.empty()) {
    const glm::vec3 c = bounds.center();
    if (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) center = c;
    const float r = 0.5f * bounds.diagonal();
    if (std::isfinite(r) && r > 0.0f) radius = r;
  }
  if (!(aspectRatio > 0.0f) || !std::isfinite(aspectRatio)) aspectRatio = 1.0f;

  Camera camera;
  camera.name = "frame bounds";
  camera.yfov = glm::radians(45.0f);
  camera.aspectRatio = aspectRatio;

  // The bounding sphere fits a cone of half-angle a when the eye is radius / sin(a) away; take the
  // narrower of the vertical and horizontal half-angles so it fits both ways (portrait images too).
  const float halfV = 0.5f * camera.yfov;
  const float halfH = std::atan(std::tan(halfV) * aspectRatio);
  const float distance = radius / std::sin(std::min(halfV, halfH));

  // From in front (+Z, looking down -Z), raised 10 degrees so floors read as floors. The sphere
  // fits from any direction at this distance, so the elevation costs nothing.
  const float elevation = glm::radians(10.0f);
  const glm::vec3 back(0.0f, std::sin(elevation), std::cos(elevation));  // from centre to eye
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), back));
  const glm::vec3 up = glm::cross(back, right);
  camera.position = center + distance * back;
  camera.orientation = glm::mat3(right, up, back);

  // Everything lies in [distance - radius, distance + radius] along the view axis; keep a margin
  // and stay well away from zero so depth precision holds.
  camera.znear = std::max(0.5f * (distance - radius), 1e-4f * distance);
  camera.zfar = 2.0f * (distance + radius);
  return camera;
}

}  // namespace lgh
