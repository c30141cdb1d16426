#include "render/camera_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lgh {

glm::dmat4 reversedZPerspective(double yfov, double aspect, double znear, double zfar) {
  const double f = 1.0 / std::tan(0.5 * yfov);
  glm::dmat4 p(0.0);
  p[0][0] = f / aspect;
  p[1][1] = f;
  p[2][3] = -1.0;  // w = -z_view = distance along the view axis
  if (std::isfinite(zfar) && zfar < 1e30) {
    // depth = znear (zfar - d) / (d (zfar - znear)): 1 at d = znear, 0 at d = zfar.
    p[2][2] = znear / (zfar - znear);
    p[3][2] = znear * zfar / (zfar - znear);
  } else {
    p[2][2] = 0.0;  // depth = znear / d
    p[3][2] = znear;
  }
  return p;
}

CameraView makeCameraView(const Camera& camera, int width, int height) {
  CameraView v;
  v.position = camera.position;
  const glm::dmat3 orientation(camera.orientation);
  const glm::dmat3 rotation = glm::transpose(orientation);  // world -> camera axes (orthonormal)
  glm::dmat4 view(rotation);
  view[3] = glm::dvec4(-(rotation * glm::dvec3(camera.position)), 1.0);
  v.view = glm::mat4(view);
  const double aspect = double(std::max(width, 1)) / double(std::max(height, 1));
  const double znear = std::max(double(camera.znear), 1e-12);
  const double zfar = std::max(double(camera.zfar), znear * (1.0 + 1e-6));
  v.znear = float(znear);
  const glm::dmat4 projection = reversedZPerspective(double(camera.yfov), aspect, znear, zfar);
  v.projection = glm::mat4(projection);
  v.cameraRelativeViewProjection = glm::mat4(projection * glm::dmat4(rotation));
  v.worldViewProjection = glm::mat4(projection * view);
  return v;
}

}  // namespace lgh
