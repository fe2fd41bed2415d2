#pragma once
// Everything one picture shows, in the floor frame (metres, y up), and nothing about how it was
// computed: the renderer never sees the physics (house style, "The renderer reads a snapshot").

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/render_settings.h"

namespace coinroll::render {

struct CoinPose {
  glm::vec3 centre{0.0f};                      // m, centre of mass
  glm::quat attitude{1.0f, 0.0f, 0.0f, 0.0f};  // body axes -> floor frame; the coin's normal is body Z
};

struct CameraView {
  glm::vec3 eye{0.0f, 0.3f, 0.6f};          // m
  glm::vec3 target{0.0f};                   // m
  float fovYDegrees = kDefaultFovYDegrees;  // vertical field of view

  bool operator==(const CameraView&) const = default;
};

// One curve of an inset plot: the whole clip, each value scaled into its own range.
struct InsetCurve {
  std::vector<glm::vec2> points;  // (x, y) in [0, 1]^2: x the clip's progress, y the value within its range
  std::string label;              // its value now and its range, drawn above the plot in the curve's colour
};

// A small plot in the picture's lower right corner (render --inset): quantities the picture cannot
// show well (a rate that outruns the slow motion, a tilt of a degree) against the clip's progress,
// the part already shown drawn solid, the rest faint, and a marker at this frame.
struct InsetPlot {
  std::vector<InsetCurve> curves;  // at most kInsetCurveColours.size(), coloured in that order
  float now = 0;                   // x of this frame, in [0, 1]
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
  // Which trace points the coin was in the air at (flight): not drawn. Empty, or one per point.
  std::vector<bool> traceFlies;
  float traceWidth = 0.0015f;  // m
  bool showContact = true;     // a marker at the newest trace point
  // Text for the corner overlay, one entry per line; empty for no overlay.
  std::vector<std::string> hudLines;
  std::optional<InsetPlot> inset;  // none: no inset plot
};

}  // namespace coinroll::render
