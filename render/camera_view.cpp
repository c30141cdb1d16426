#include "render/camera_view.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace lgh {

CameraView makeCameraView(const Camera& camera, int width, int height) {
  CameraView v;
  v.position = camera.position;
  glm::mat4 cameraToWorld(camera.orientation);
  cameraToWorld[3] = glm::vec4(camera.position, 1.0f);
  v.view = glm::inverse(cameraToWorld);
  const float aspect = float(std::max(width, 1)) / float(std::max(height, 1));
  const float znear = std::max(camera.znear, 1e-6f);
  const float zfar = std::max(camera.zfar, znear * 2.0f);
  v.projection = glm::perspective(camera.yfov, aspect, znear, zfar);
  return v;
}

}  // namespace lgh
