#pragma once
// Everything one picture shows, in the floor frame (metres, y up), and nothing about how it was
// computed: the renderer never sees the physics (house style, "The renderer reads a snapshot").

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "render/render_settings.h"

namespace coinroll::render {

struct CoinPose {
  glm::vec3 centre{0.0f};                       // m, centre of mass
  glm::quat attitude{1.0f, 0.0f, 0.0f, 0.0f};   // body axes -> floor frame; the coin's normal is body Z
};

struct CameraView {
  glm::vec3 eye{0.0f, 0.3f, 0.6f};  // m
  glm::vec3 target{0.0f};           // m
  float fovYDegrees = kDefaultFovYDegrees;  // vertical field of view

  bool operator==(const CameraView&) const = default;
};

struct FrameSnapshot {
  CameraView camera;
  CoinPose coin;
  // Earlier poses drawn semi-transparent, for stroboscopic figures; oldest first, tinted by age from
  // dark blue (oldest) through grey to yellow (newest).
  std::vector<CoinPose> ghosts;
  // Contact points (x, z) on the floor, oldest first, evenly spaced in time; the newest is the
  // current contact point. Drawn as a ribbon that fades with age.
  std::vector<glm::vec2> trace;
  // Which trace points the coin slid at (the contact slipping): drawn in another colour. Empty, or
  // one entry per trace point.
  std::vector<bool> traceSlides;
  float traceWidth = 0.0015f;  // m
  bool showContact = true;     // a marker at the newest trace point
  // Text for the corner overlay, one entry per line; empty for no overlay.
  std::vector<std::string> hudLines;
};

}  // namespace coinroll::render
