#include "pipeline/motion_survey.h"

#include <algorithm>
#include <cmath>

#include "pipeline/coin_run.h"

namespace coinroll::pipeline {

double traceInterval(double duration) { return std::max(1.0 / 240, duration / 20000); }

MotionSurvey surveyMotion(const Simulation& simulation) {
  CoinRun trajectory(simulation);
  MotionSurvey survey;
  survey.lower = survey.upper = trajectory.sampleAt(0)->forward.centre;
  const double dt = traceInterval(simulation.duration);
  const long samples = static_cast<long>(std::floor(simulation.duration / dt));
  survey.endTime = simulation.duration;
  for (long k = 0; k <= samples + 1; ++k) {
    const double t = std::min(static_cast<double>(k) * dt, simulation.duration);
    const std::optional<RunSample> sample = trajectory.sampleAt(t);
    if (!sample) break;
    for (const Eigen::Vector3d& p : {sample->forward.centre, sample->forward.contactPoint}) {
      survey.lower = survey.lower.cwiseMin(p);
      survey.upper = survey.upper.cwiseMax(p);
    }
  }
  if (trajectory.stoppedBy()) {
    survey.stoppedBy = trajectory.stoppedBy();
    survey.endTime = trajectory.stoppedBy()->t;
  }
  return survey;
}

}  // namespace coinroll::pipeline
