#pragma once
// From the physics to what the renderer reads: coin poses, trace points, overlay text, and a
// camera that frames the whole motion (so the first frame already knows where the coin will go).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "pipeline/simulation.h"
#include "render/frame_snapshot.h"
#include "render/renderer.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

render::CoinPose coinPose(const physics::CoinModel& model, const physics::CoinState& state);

// Contact point on the floor as (x, z).
Eigen::Vector2d contactOnFloor(const physics::CoinModel& model, const physics::CoinState& state);

// Overlay lines: time, tilt, spin rate psi-dot, energy; plus `extra` lines (e.g. slow motion).
std::vector<std::string> hudLines(const physics::CoinModel& model, const physics::CoinState& state, double time,
                                  const std::vector<std::string>& extra = {});

// Simulated seconds between trace points: fine enough that the ribbon looks smooth at any
// frame rate, coarse enough that a long run stays under ~20,000 points.
double traceInterval(double duration);

// Where the motion goes: a first pass over the whole run at the trace interval.
struct MotionSurvey {
  Eigen::Vector3d lower, upper;  // m, box around every centre of mass and contact point
  double endTime = 0;            // s, the duration, or when a validity event stopped the run
  std::optional<integrate::EventHit<physics::kStateSize>> stoppedBy;
};
MotionSurvey surveyMotion(const Simulation& simulation);

// The scene's render.camera turned into a view per time: fixed (framing the survey box), orbit
// (the same distance, circling the box once per orbit period) or follow (tracking the coin).
class CameraRig {
 public:
  CameraRig(const scene::CameraSpec& spec, const MotionSurvey& survey, const physics::CoinModel& model, int width,
            int height);
  render::CameraView at(double time, const physics::CoinState& state) const;

 private:
  scene::CameraSpec spec_;
  physics::CoinModel model_;
  Eigen::Vector3d target_;
  double distance_ = 1;     // m
  double followDistance_ = 1;  // m
};

render::RenderSettings renderSettings(const scene::SceneConfig& scene);

// Ribbon width for the trace: about 2.5 pixels at the camera target, at least a twentieth of the
// coin radius.
float traceWidthFor(const render::CameraView& view, int height, double coinRadius);

}  // namespace coinroll::pipeline
