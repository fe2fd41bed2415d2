#pragma once
// The camera's matrices, shared by the renderer and by tests that check where a world point
// lands in the image.

#include <glm/glm.hpp>

#include "render/frame_snapshot.h"

namespace coinroll::render {

struct CameraMatrices {
  glm::mat4 view;
  glm::mat4 projection;
};

// Where the depth buffer's range starts and ends: bracketing the target distance generously (the
// floor fades into fog long before the far plane).
struct ClipPlanes {
  float near, far;  // m
};
ClipPlanes clipPlanes(const CameraView& camera);

// The view's "up": the floor's y, or -z looking straight down, where y says nothing.
glm::vec3 upOf(const CameraView& camera);

// Right-handed look-at with the floor's y up; near and far planes bracket the target distance
// generously (the floor fades into fog long before the far plane).
CameraMatrices cameraMatrices(const CameraView& camera, int width, int height);

// Pixel coordinates (x right, y down, origin at the top-left corner of the top-left pixel) of
// a world point.
glm::vec2 pixelFromWorld(const CameraView& camera, int width, int height, const glm::vec3& world);

}  // namespace coinroll::render
