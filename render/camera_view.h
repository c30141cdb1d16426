#pragma once
// A scene camera turned into the matrices of one image.

#include <glm/glm.hpp>

#include "render/scene/scene.h"

namespace lgh {

struct CameraView {
  glm::vec3 position{0.0f};
  glm::mat4 view{1.0f}, projection{1.0f};
  glm::mat4 viewProjection() const { return projection * view; }
};

// Uses the camera's vertical field of view with the image's aspect ratio (width / height).
CameraView makeCameraView(const Camera& camera, int width, int height);

}  // namespace lgh
