#include "pipeline/motion_survey.h"

#include <algorithm>

#include "pipeline/run_record.h"

namespace coinroll::pipeline {

double traceInterval(double duration) { return std::max(1.0 / 240, duration / 20000); }

MotionSurvey surveyMotion(const Simulation& simulation) {
  FixedFrameTimes none({});
  return recordRun(simulation, none).survey;
}

}  // namespace coinroll::pipeline
