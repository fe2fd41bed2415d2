#include "pipeline/snapshot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "physics/flight.h"
#include "render/overlay_text.h"

namespace coinroll::pipeline {

namespace {

render::CoinPose coinPose(const FrameState& frame) {
  const Eigen::Vector3d& centre = frame.centre;
  return {glm::vec3(static_cast<float>(centre.x()), static_cast<float>(centre.y()), static_cast<float>(centre.z())),
          frame.attitude};
}

// In the air: the coin's plane above the floor (rad, in [0, pi/2], from its axis alone, whichever
// way it has turned over) and the height of the rim's lowest point (m). They follow from the drawn
// pose, which is all FrameState keeps of the attitude: its fixed few bytes bound a clip's memory.
double tiltAboveFloor(const FrameState& frame) {
  const glm::vec3 axis = frame.attitude * glm::vec3(0, 0, 1);
  return std::atan2(std::hypot(static_cast<double>(axis.x), static_cast<double>(axis.z)),
                    std::abs(static_cast<double>(axis.y)));
}
double rimHeight(const physics::CoinModel& model, const FrameState& frame) {
  const Eigen::Quaterniond attitude(frame.attitude.w, frame.attitude.x, frame.attitude.y, frame.attitude.z);
  return frame.centre.y() - physics::lowestPointDepth(model, attitude.normalized());
}

// A rate that rounds to zero is shown as 0.00, never as -0.00.
double shownToTwoDecimals(double value) { return std::abs(value) < 0.005 ? 0.0 : value; }

// Overlay lines: time, tilt, the contact point's rate, the face's spin, energy (and power
// dissipated, and the slip while sliding), then `extra`.
std::vector<std::string> hudLines(const physics::CoinModel& model, const FrameState& frame,
                                  const std::vector<std::string>& extra) {
  // Near flat psi-dot grows with the contact point's rate while the face itself turns slowly, so
  // the overlay names what it shows: Omega = phi-dot (the contact point round the floor, in Hz,
  // what the ear hears and the eye follows) and the face's own turning omega_Z = psi-dot - phi-dot sin(theta),
  // both in Hz, so that the two rates read side by side. A coin that rocks rather than precesses has
  // no contact rate to show (physics::axisGoesRound).
  // In the air there is no contact and the seed's theta (from vertical, for a coin on its rim) does
  // not say how a tumbling coin lies: the tilt comes from the axis, and the rim's height replaces
  // the contact's rate.
  constexpr double kTurn = 2 * std::numbers::pi;
  std::vector<std::string> lines = {fmt::format("t        {:9.3f} s", frame.time)};
  if (frame.flying) {
    lines.push_back(fmt::format("tilt     {:9.2f}° above the floor", tiltAboveFloor(frame) * 180 / std::numbers::pi));
    lines.push_back(fmt::format("rim      {:9.2f} mm above the floor, in the air", 1e3 * rimHeight(model, frame)));
  } else {
    // The scene's theta (from vertical), and the tilt above the floor a spin-down is read by.
    lines.push_back(fmt::format("θ        {:9.2f}° from vertical, {:.2f}° above the floor",
                                shownToTwoDecimals(frame.theta * 180 / std::numbers::pi),
                                90 - std::abs(frame.theta) * 180 / std::numbers::pi));
    lines.push_back(frame.axisGoesRound
                        ? fmt::format("contact  {:9.2f} Hz round the floor", std::abs(frame.precessionRate) / kTurn)
                        : std::string("contact         -- rocking, not going round"));
  }
  lines.push_back(fmt::format("face     {:9.2f} Hz about its axis", shownToTwoDecimals(frame.omega_Z / kTurn)));
  lines.push_back(fmt::format("E        {:9.5f} J", frame.energy));
  if (!model.effects.empty()) lines.push_back(fmt::format("P        {:9.3f} mW dissipated", 1e3 * frame.power));
  // What is drawn is what is simulated: a sliding coin says so, with the slip of its contact.
  if (frame.sliding) lines.push_back(fmt::format("sliding  {:9.2f} mm/s slip", 1e3 * frame.slipSpeed));
  // With flight, the phase and the bounces so far (the trace under a flying coin is its rim's lowest
  // point seen from above).
  if (frame.flying || frame.impacts > 0) {
    lines.push_back(fmt::format("{:<8} {:9d} impact{}", frame.flying ? "flight" : "landed", frame.impacts,
                                frame.impacts == 1 ? "" : "s"));
  }
  lines.insert(lines.end(), extra.begin(), extra.end());
  return lines;
}

}  // namespace

std::vector<std::string> panelLabel(const physics::CoinModel& model, const FrameState& frame) {
  std::vector<std::string> lines = {fmt::format("t = {:.3f} s", frame.time)};
  if (frame.flying) {
    lines.push_back(fmt::format("{:.2f}° above the floor", tiltAboveFloor(frame) * 180 / std::numbers::pi));
    lines.push_back(fmt::format("rim {:.1f} mm up, in the air", 1e3 * rimHeight(model, frame)));
  } else {
    lines.push_back(fmt::format("{:.2f}° above the floor", 90 - std::abs(frame.theta) * 180 / std::numbers::pi));
    lines.push_back(fmt::format("contact {:.1f} Hz", std::abs(frame.precessionRate) / (2 * std::numbers::pi)));
  }
  return lines;
}

namespace {

// Ribbon width for the trace: about 2.5 pixels at the camera target, at least a twentieth of the
// coin radius.
float traceWidthFor(const render::CameraView& view, int height, double coinRadius) {
  const float metresPerPixel = 2.0f * glm::length(view.eye - view.target) *
                               std::tan(glm::radians(0.5f * view.fovYDegrees)) / static_cast<float>(height);
  return std::max(2.5f * metresPerPixel, 0.05f * static_cast<float>(coinRadius));
}

}  // namespace

SnapshotMaker::SnapshotMaker(const scene::SceneConfig& scene, const physics::CoinModel& model, const RunRecord& record)
    : model_(model),
      record_(record),
      camera_(scene.render.camera),
      rig_(scene.render.camera, record.survey, model, scene.render.picture.width, scene.render.picture.height),
      traceDt_(traceInterval(scene.duration)),
      showTrace_(scene.render.trace),
      showHud_(scene.render.hud),
      width_(scene.render.picture.width),
      height_(scene.render.picture.height) {
  snapshot_.showContact = showTrace_;
}

void SnapshotMaker::extendTraceTo(double time) {
  if (!showTrace_) return;
  // The contact point of the previous snapshot is off the trace's grid of times: replace it.
  if (traceEndsWithNow_) {
    snapshot_.trace.pop_back();
    snapshot_.traceSlides.pop_back();
    snapshot_.traceFlies.pop_back();
  }
  traceEndsWithNow_ = false;
  for (; static_cast<double>(nextTracePoint_) * traceDt_ < time; ++nextTracePoint_) {
    if (nextTracePoint_ >= record_.trace.size()) {
      throw std::logic_error(fmt::format("snapshots: no trace point recorded at t = {} s, before the frame at {} s",
                                         static_cast<double>(nextTracePoint_) * traceDt_, time));
    }
    snapshot_.trace.push_back(record_.trace[nextTracePoint_]);
    snapshot_.traceSlides.push_back(record_.traceSlides[nextTracePoint_]);
    snapshot_.traceFlies.push_back(record_.traceFlies[nextTracePoint_]);
  }
}

void SnapshotMaker::markInset(float now, const std::vector<std::string>& labels) {
  snapshot_.inset->now = now;
  for (std::size_t i = 0; i < labels.size() && i < snapshot_.inset->curves.size(); ++i)
    snapshot_.inset->curves[i].label = labels[i];
}

void SnapshotMaker::addGhost(const FrameState& frame) { snapshot_.ghosts.push_back(coinPose(frame)); }

void SnapshotMaker::frameCopies(const std::vector<FrameState>& frames, const std::vector<std::string>& extraHudLines) {
  MotionSurvey box{.lower = frames.at(0).centre, .upper = frames.at(0).centre};
  for (const FrameState& frame : frames) {
    box.lower = box.lower.cwiseMin(frame.centre);
    box.upper = box.upper.cwiseMax(frame.centre);
  }
  // The rig widens the box by the radius sideways only: a coin standing on its rim at the top of an
  // arc reaches a radius above its centre.
  box.upper.y() += model_.a;
  // The overlay sits in the picture's top left: the box is raised by as much as keeps the band the
  // overlay's height takes (its margin above and below it) clear of the copies. The rig fits the box
  // from the floor up to its top plus a fifth of the radius (camera_rig.cpp); 1 / (1 - band) of
  // that height fills the picture when its top `band` is left empty.
  if (showHud_) {
    const render::GlyphAtlas atlas(render::overlayTextPixels(height_));
    const float overlayBottom = 2 * std::round(0.5f * atlas.lineHeight()) +
                                render::textPanelSize(atlas, hudLines(model_, frames.back(), extraHudLines)).y;
    // A small picture's overlay can take most of its height: the copies keep its lower half at least.
    const double band = std::min(0.5, static_cast<double>(overlayBottom) / height_);
    const double fitted = std::max(box.upper.y(), model_.a) + 0.2 * model_.a;
    box.upper.y() = fitted / (1 - band) - 0.2 * model_.a;
  }
  // From the direction the scene's camera looks in when it gives one (a follow camera's offset).
  std::optional<Eigen::Vector3d> towardsEye;
  if (camera_.eye && camera_.target) {
    towardsEye = (Eigen::Vector3d(camera_.eye->data()) - Eigen::Vector3d(camera_.target->data())).normalized();
  }
  scene::CameraSpec fixed = camera_;
  fixed.mode = scene::CameraMode::Fixed;
  fixed.eye.reset();
  fixed.target.reset();
  rig_ = CameraRig(fixed, box, model_, width_, height_, towardsEye);
}

const render::FrameSnapshot& SnapshotMaker::makeSnapshot(const FrameState& frame,
                                                         const std::vector<std::string>& extraHudLines) {
  extendTraceTo(frame.time);
  if (showTrace_) {
    snapshot_.trace.push_back(frame.contact);
    snapshot_.traceSlides.push_back(frame.sliding);
    snapshot_.traceFlies.push_back(frame.flying);
    traceEndsWithNow_ = true;
  }
  snapshot_.coin = coinPose(frame);
  snapshot_.camera = rig_.at(frame.time, frame.centre);
  snapshot_.traceWidth = traceWidthFor(snapshot_.camera, height_, model_.a);
  if (showHud_) snapshot_.hudLines = hudLines(model_, frame, extraHudLines);
  return snapshot_;
}

}  // namespace coinroll::pipeline
