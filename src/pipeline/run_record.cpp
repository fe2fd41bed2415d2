#include "pipeline/run_record.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/observables.h"

namespace coinroll::pipeline {

FrameState frameStateOf(double time, const RunSample& sample) {
  const Eigen::Quaterniond q = physics::attitude(sample.state);
  const physics::Forward& f = sample.forward;
  return {.time = time,
          .centre = f.centre,
          .attitude = glm::quat(static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
                                static_cast<float>(q.z())),
          .contact = {static_cast<float>(f.contactPoint.x()), static_cast<float>(f.contactPoint.z())},
          .theta = sample.state.theta,
          .omega_Z = sample.state.omega_Z,
          .precessionRate = f.precessionRate,
          .energy = f.energy,
          .power = f.loads.power,
          .slipSpeed = f.slip.norm(),
          .sliding = f.sliding,
          .flying = f.flying,
          .axisGoesRound = physics::axisGoesRound(f),
          .impacts = sample.impacts};
}

void addSurveySample(RunRecord& record, const RunSample& sample, bool first, bool onGrid) {
  MotionSurvey& survey = record.survey;
  if (first) survey.lower = survey.upper = sample.forward.centre;
  for (const Eigen::Vector3d& p : {sample.forward.centre, sample.forward.contactPoint}) {
    survey.lower = survey.lower.cwiseMin(p);
    survey.upper = survey.upper.cwiseMax(p);
  }
  if (onGrid) {
    record.trace.emplace_back(static_cast<float>(sample.forward.contactPoint.x()),
                              static_cast<float>(sample.forward.contactPoint.z()));
    record.traceSlides.push_back(sample.forward.sliding);
    record.traceFlies.push_back(sample.forward.flying);
  }
}

std::optional<double> FixedFrameTimes::timeOf(long k, const RunSample*) {
  if (k >= static_cast<long>(times_.size())) return std::nullopt;
  return times_[static_cast<std::size_t>(k)];
}

namespace {

// The pass's state. Samples are asked for in increasing time (the grid's and the frames' merged):
// a CoinRun cannot go back, and once a query has gone past an event nothing after it is answered,
// so the sample at the run's end comes from the event itself (the same dense output at the same
// time, hence the same numbers as a query there).
class Pass {
 public:
  Pass(const Simulation& simulation, FramePlan& plan)
      : run_(simulation),
        plan_(plan),
        duration_(simulation.duration),
        dt_(traceInterval(simulation.duration)),
        lastGrid_(static_cast<long>(std::floor(simulation.duration / dt_)) + 1),
        end_(simulation.duration) {}

  RunRecord record() {
    nextFrame_ = plan_.timeOf(0, nullptr);
    while (!gridDone_ || nextFrame_) {
      const double gridTime = gridDone_ ? std::numeric_limits<double>::infinity()
                                        : std::min(static_cast<double>(gridIndex_) * dt_, duration_);
      if (nextFrame_ && *nextFrame_ < gridTime)
        takeFrame(*nextFrame_);
      else
        takeGridPoint(gridTime);
    }
    if (const std::optional<RunEvent> stop = run_.stoppedBy()) {
      record_.survey.stoppedBy = stop;
      record_.survey.endTime = stop->t;
      // An event exactly at the duration is met without a query past it: the duration's sample is the end.
      if (!endSample_) endSample_ = RunSample{stop->state, stop->forward, stop->dissipated};
    } else {
      record_.survey.endTime = duration_;
    }
    record_.end = frameStateOf(record_.survey.endTime, endSample_ ? *endSample_ : *atDuration_);
    record_.stats = run_.stats();
    record_.impacts = run_.impacts();
    return std::move(record_);
  }

 private:
  // The sample at t, or none once the run has ended before t (the end is then known).
  std::optional<RunSample> query(double t) {
    if (ended_) return std::nullopt;
    std::optional<RunSample> sample = run_.sampleAt(t);
    if (sample) return sample;
    ended_ = true;
    // A run stopped past its duration (found by a remapped frame just beyond it) ends at the duration.
    if (const std::optional<RunEvent> stop = run_.stoppedBy()) {
      end_ = stop->t;
      endSample_ = RunSample{stop->state, stop->forward, stop->dissipated};
    }
    return std::nullopt;
  }

  // Survey points: every traceInterval, then the duration; the first to fail ends them.
  void takeGridPoint(double t) {
    const std::optional<RunSample> sample = query(t);
    if (!sample) {
      gridDone_ = true;
      return;
    }
    addSurveySample(record_, *sample, gridIndex_ == 0, static_cast<double>(gridIndex_) * dt_ == t);
    if (t == duration_) atDuration_ = sample;
    if (++gridIndex_ > lastGrid_) gridDone_ = true;
  }

  void takeFrame(double t) {
    const std::optional<RunSample> sample = query(t);
    // Until a query fails, a run that answered at t ends at or after t: the duration stands for its end.
    const double end = end_;
    if (!plan_.keeps(frameIndex_, t, end)) {
      nextFrame_.reset();
      return;
    }
    const RunSample& shown = sample && t <= end ? *sample : endSample_ ? *endSample_ : *atDuration_;
    record_.frames.push_back(frameStateOf(std::min(t, end), shown));
    ++frameIndex_;
    nextFrame_ = plan_.timeOf(frameIndex_, sample ? &*sample : nullptr);
  }

  CoinRun run_;
  FramePlan& plan_;
  double duration_;  // s
  double dt_;        // s, traceInterval
  long lastGrid_;    // the survey's last point, at the duration
  long gridIndex_ = 0;
  bool gridDone_ = false;
  long frameIndex_ = 0;
  std::optional<double> nextFrame_;  // s, the next frame's time
  bool ended_ = false;               // a query went past the run's end
  double end_;                       // s, the duration, or the event's time once a query went past it
  std::optional<RunSample> endSample_, atDuration_;
  RunRecord record_;
};

}  // namespace

RunRecord recordRun(const Simulation& simulation, FramePlan& plan) { return Pass(simulation, plan).record(); }

}  // namespace coinroll::pipeline
