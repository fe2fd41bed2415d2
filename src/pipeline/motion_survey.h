#pragma once
// Where the motion goes: what the whole run covers, so the camera of the first frame already
// frames everything the coin will do, and the frame loop knows where the run ends. Recorded by the
// one pass over the run (pipeline/run_record.h).

#include <Eigen/Core>
#include <optional>

#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// Simulated seconds between trace points (and between the survey's samples): fine enough that
// the ribbon looks smooth at any frame rate, coarse enough that a long run stays under ~20,000
// points.
double traceInterval(double duration);

struct MotionSurvey {
  Eigen::Vector3d lower = Eigen::Vector3d::Zero(),
                  upper = Eigen::Vector3d::Zero();  // m, box around every centre of mass and contact point
  double endTime = 0;                               // s, the duration, or when a validity event stopped the run
  std::optional<RunEvent> stoppedBy = {};
};

// The survey alone: the run sampled every traceInterval and at its end, and no frames.
MotionSurvey surveyMotion(const Simulation& simulation);

}  // namespace coinroll::pipeline
