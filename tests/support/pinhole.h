#pragma once
// The render tests' oracle for where a point should appear: a pinhole camera written here from the
// camera's definition (eye, target, floor +y up, vertical field of view, square pixels), in
// doubles, without the renderer's matrices (render/camera.h), so a mistake there cannot cancel out.
// Header-only: only the render tests, which link coinroll_render (glm), include it.

#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

#include "render/frame_snapshot.h"

namespace coinroll::testing {

// Pixel coordinates: x right, y down, origin at the top-left corner of the top-left pixel (so
// pixel (i, j) covers [i, i+1) x [j, j+1) and its centre is (i + 0.5, j + 0.5)), as camera.h's.
inline glm::dvec2 pinholePixel(const render::CameraView& camera, int width, int height, const glm::dvec3& world) {
  const glm::dvec3 eye(camera.eye), target(camera.target);
  // Look-at basis: forward towards the target, right = forward x up, the camera's up completes it.
  const glm::dvec3 forward = glm::normalize(target - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, forward);
  const glm::dvec3 d = world - eye;
  const double depth = glm::dot(d, forward);
  // Focal length in pixels: half the image height subtends half the vertical field of view.
  const double focal = 0.5 * height / std::tan(0.5 * double(camera.fovYDegrees) * std::numbers::pi / 180);
  return {0.5 * width + focal * glm::dot(d, right) / depth, 0.5 * height - focal * glm::dot(d, up) / depth};
}

}  // namespace coinroll::testing
