#include "pipeline/snapshot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pipeline/overlay_lines.h"
#include "render/overlay_text.h"

namespace coinroll::pipeline {

namespace {

render::CoinPose coinPose(const FrameState& frame) {
  const Eigen::Vector3d& centre = frame.centre;
  return {glm::vec3(static_cast<float>(centre.x()), static_cast<float>(centre.y()), static_cast<float>(centre.z())),
          frame.attitude};
}

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
