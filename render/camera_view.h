#pragma once
// A scene camera turned into the matrices of one image.
//
// Depth: reversed Z (the near plane maps to depth 1, the far plane to 0, an absent far plane to an
// infinite projection) for a DEPTH_COMPONENT32F buffer with glClipControl(GL_ZERO_TO_ONE): float
// depth keeps ~24 bits of relative precision at every distance, so znear/zfar = 1e-3/1e7 resolves
// surfaces as well as 0.1/100 does. With the default [-1, 1] clip range (passes other than the
// G-buffer) the same matrix clips at the near plane and never at the far one.
// Transforms are composed in double; cameraRelativeViewProjection leaves the translation out, so the
// G-buffer subtracts the camera position from each vertex first (exact for nearby vertices, Sterbenz)
// instead of rounding a large translation into the matrix.

#include <glm/glm.hpp>

#include "render/scene/scene.h"

namespace lgh {

struct CameraView {
  glm::vec3 position{0.0f};  // scene space
  glm::mat4 view{1.0f}, projection{1.0f};
  glm::mat4 cameraRelativeViewProjection{1.0f};  // projection x rotation: clip = M (p - position)
  glm::mat4 worldViewProjection{1.0f};           // projection x view, composed in double
  float znear = 0.01f;                           // clip w of the near plane: every rasterized surface has w >= znear
  glm::mat4 viewProjection() const { return worldViewProjection; }
};

// Uses the camera's vertical field of view with the image's aspect ratio (width / height).
CameraView makeCameraView(const Camera& camera, int width, int height);

// Reversed-Z perspective projection for GL_ZERO_TO_ONE depth: depth = 1 at znear, 0 at zfar
// (an infinite far plane when zfar is infinite or beyond float range).
glm::dmat4 reversedZPerspective(double yfov, double aspect, double znear, double zfar);

}  // namespace lgh
