#include "pipeline/snapshot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include "physics/observables.h"

namespace coinroll::pipeline {

namespace {

render::CoinPose coinPose(const RunSample& sample) {
  const Eigen::Quaterniond q = physics::attitude(sample.state);
  const Eigen::Vector3d& centre = sample.forward.centre;
  return {glm::vec3(static_cast<float>(centre.x()), static_cast<float>(centre.y()), static_cast<float>(centre.z())),
          glm::quat(static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()))};
}

// The contact point on the floor as (x, z).
glm::vec2 contactOnFloor(const physics::Forward& forward) {
  return {static_cast<float>(forward.contactPoint.x()), static_cast<float>(forward.contactPoint.z())};
}

// A rate that rounds to zero is shown as 0.00, never as -0.00.
double shownToTwoDecimals(double value) { return std::abs(value) < 0.005 ? 0.0 : value; }

// Overlay lines: time, tilt, the contact point's rate, the face's spin, energy (and power
// dissipated, and the slip while sliding), then `extra`.
std::vector<std::string> hudLines(const physics::CoinModel& model, const RunSample& sample, double time,
                                  const std::vector<std::string>& extra) {
  const physics::CoinState& state = sample.state;
  const physics::Forward& f = sample.forward;
  // Near flat psi-dot grows with the contact point's rate while the face itself turns slowly, so
  // the overlay names what it shows: Omega = phi-dot (the contact point round the floor, in Hz,
  // what the ear hears and the eye follows) and the face's own turning omega_Z = psi-dot - phi-dot sin(theta),
  // both in Hz, so that the two rates read side by side. A coin that rocks rather than precesses has
  // no contact rate to show (physics::axisGoesRound).
  constexpr double kTurn = 2 * std::numbers::pi;
  std::vector<std::string> lines = {
      fmt::format("t        {:9.3f} s", time),
      fmt::format("θ        {:9.2f}° from vertical", shownToTwoDecimals(state.theta * 180 / std::numbers::pi)),
      physics::axisGoesRound(f) ? fmt::format("contact  {:9.2f} Hz round the floor", std::abs(f.precessionRate) / kTurn)
                                : std::string("contact         -- rocking, not going round"),
      fmt::format("face     {:9.2f} Hz about its axis", shownToTwoDecimals(state.omega_Z / kTurn)),
      fmt::format("E        {:9.5f} J", f.energy),
  };
  if (!model.effects.empty()) lines.push_back(fmt::format("P        {:9.3f} mW dissipated", 1e3 * f.loads.power));
  // What is drawn is what is simulated: a sliding coin says so, with the slip of its contact.
  if (f.sliding) lines.push_back(fmt::format("sliding  {:9.2f} mm/s slip", 1e3 * f.slip.norm()));
  lines.insert(lines.end(), extra.begin(), extra.end());
  return lines;
}

// Ribbon width for the trace: about 2.5 pixels at the camera target, at least a twentieth of the
// coin radius.
float traceWidthFor(const render::CameraView& view, int height, double coinRadius) {
  const float metresPerPixel =
      2.0f * glm::length(view.eye - view.target) * std::tan(glm::radians(0.5f * view.fovYDegrees)) / static_cast<float>(height);
  return std::max(2.5f * metresPerPixel, 0.05f * static_cast<float>(coinRadius));
}

}  // namespace

SnapshotMaker::SnapshotMaker(const scene::SceneConfig& scene, const Simulation& simulation, const MotionSurvey& survey)
    : model_(simulation.model),
      run_(simulation),
      rig_(scene.render.camera, survey, simulation.model, scene.render.picture.width, scene.render.picture.height),
      traceDt_(traceInterval(simulation.duration)),
      showTrace_(scene.render.trace),
      showHud_(scene.render.hud),
      height_(scene.render.picture.height) {
  snapshot_.showContact = showTrace_;
}

RunSample SnapshotMaker::sampleAt(double time) {
  std::optional<RunSample> sample = run_.sampleAt(time);
  if (!sample) throw std::logic_error(fmt::format("snapshots: the run ended before t = {} s, where the survey said it goes on", time));
  return std::move(*sample);
}

void SnapshotMaker::extendTraceTo(double time) {
  if (!showTrace_) return;
  // The contact point of the previous snapshot is off the trace's grid of times: replace it.
  if (traceEndsWithNow_) {
    snapshot_.trace.pop_back();
    snapshot_.traceSlides.pop_back();
  }
  traceEndsWithNow_ = false;
  for (; static_cast<double>(nextTracePoint_) * traceDt_ < time; ++nextTracePoint_) {
    const physics::Forward forward = sampleAt(static_cast<double>(nextTracePoint_) * traceDt_).forward;
    snapshot_.trace.push_back(contactOnFloor(forward));
    snapshot_.traceSlides.push_back(forward.sliding);
  }
}

void SnapshotMaker::addGhost(double time) {
  extendTraceTo(time);  // the run streams: earlier trace points first
  snapshot_.ghosts.push_back(coinPose(sampleAt(time)));
}

const render::FrameSnapshot& SnapshotMaker::makeSnapshot(double time, const std::vector<std::string>& extraHudLines) {
  extendTraceTo(time);
  sample_ = sampleAt(time);
  if (showTrace_) {
    snapshot_.trace.push_back(contactOnFloor(sample_.forward));
    snapshot_.traceSlides.push_back(sample_.forward.sliding);
    traceEndsWithNow_ = true;
  }
  snapshot_.coin = coinPose(sample_);
  snapshot_.camera = rig_.at(time, sample_.forward.centre);
  snapshot_.traceWidth = traceWidthFor(snapshot_.camera, height_, model_.a);
  if (showHud_) snapshot_.hudLines = hudLines(model_, sample_, time, extraHudLines);
  return snapshot_;
}

}  // namespace coinroll::pipeline
