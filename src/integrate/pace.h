#pragma once
// Whether a run's steps to its end would pass the steps a run may take, decided early: one
// Trajectory's steps, or a HybridRun's over all its segments (a toss rolling on its edge makes
// thousands of short segments, none of which alone ever looks hopeless).

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace coinroll::integrate {

class PaceWatch {
 public:
  // s, where the run starts and is asked to end (infinite: never decided); the steps it may take.
  PaceWatch(double t0, double endTime, long maxSteps) : t0_(t0), endTime_(endTime), maxSteps_(maxSteps) {
    last_ = earlier_ = {0, t0};
  }

  // The run has taken `steps` accepted steps in all and reached t. Called after every step, or
  // less often (at each segment's end): the checkpoints are where the count first reaches each
  // power of two, so the checks cost nothing. Throws std::runtime_error past maxSteps, and when, at
  // a checkpoint of at least 1024 steps, either ground holds:
  // - a hundredth of the run done: its average pace so far, projected, needs more than maxSteps (a
  //   short start-up transient does not decide);
  // - a hundredth of maxSteps taken, at a pace that is not rising: the pace since the last
  //   checkpoint, projected over what is left, needs more. This decides within a second or two of
  //   wall time however long the run (the 1 % above takes minutes when the end is far: 1000 s of a
  //   ring at 1e6 rad/s). A rising pace is left to the first ground: it is how a coin approaches
  //   falling flat or a spin-down's singular time, whose event ends the run long before a far end,
  //   so projecting it would refuse runs that finish. The pace between the two checkpoints before
  //   counts as rising past 5 %: round-off and wobbles move it by less.
  void afterSteps(long steps, double t) {
    if (steps > maxSteps_) {
      throw std::runtime_error(fmt::format("integration needs more than {} steps: stopped at t = {} s", maxSteps_, t));
    }
    if (steps < nextCheckpoint_) return;
    const Checkpoint last = last_, earlier = earlier_;
    earlier_ = last_;
    last_ = {steps, t};
    while (nextCheckpoint_ <= steps) nextCheckpoint_ *= 2;
    if (!std::isfinite(endTime_) || steps < 1024) return;
    const double done = t - t0_, whole = endTime_ - t0_, left = endTime_ - t;
    const double limit = static_cast<double>(maxSteps_);
    double projected = 0;
    if (done >= 0.01 * whole) {
      projected = static_cast<double>(steps) * whole / done;
    } else if (static_cast<double>(steps) >= 0.01 * limit && t > last.t && last.t > earlier.t) {
      const double pace = static_cast<double>(steps - last.steps) / (t - last.t);  // steps per s
      const double earlierPace = static_cast<double>(last.steps - earlier.steps) / (last.t - earlier.t);
      if (pace <= 1.05 * earlierPace) projected = static_cast<double>(steps) + pace * left;
    }
    if (projected > limit) {
      throw std::runtime_error(fmt::format(
          "integration would need about {:.2g} steps to reach t = {} s at its pace so far ({} steps for the first "
          "{:.6g} s), more than the {} a run may take; shorten the duration, or loosen solver.rtol and solver.atol",
          projected, endTime_, steps, done, maxSteps_));
    }
  }

 private:
  struct Checkpoint {
    long steps;
    double t;  // s
  };
  double t0_, endTime_;  // s
  long maxSteps_;
  long nextCheckpoint_ = 1;
  Checkpoint last_, earlier_;  // the latest two checkpoints
};

}  // namespace coinroll::integrate
