#pragma once
// Where the motion goes: a first pass over the whole run, so the camera of the first frame already
// frames everything the coin will do, and the frame loop knows where the run ends.

#include <Eigen/Core>
#include <optional>

#include "integrate/events.h"
#include "physics/coin_state.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// Simulated seconds between trace points (and between the survey's samples): fine enough that
// the ribbon looks smooth at any frame rate, coarse enough that a long run stays under ~20,000
// points.
double traceInterval(double duration);

struct MotionSurvey {
  Eigen::Vector3d lower, upper;  // m, box around every centre of mass and contact point
  double endTime = 0;            // s, the duration, or when a validity event stopped the run
  std::optional<RunEvent> stoppedBy;
};

// Samples the run every traceInterval and at its end.
MotionSurvey surveyMotion(const Simulation& simulation);

}  // namespace coinroll::pipeline
