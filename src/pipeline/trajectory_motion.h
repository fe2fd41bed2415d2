#pragma once
// A Motion that is one integrator's trajectory: samples, end and crossings of an integrated state
// that `Kind` reads in the seed's variables. Each formulation's run (formulation_run.h) and each
// contact mode of a HybridRun is one of these, so the hits become RunEvents here only.

#include <optional>
#include <utility>
#include <vector>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "integrate/trajectory.h"
#include "physics/coin_state.h"
#include "pipeline/motion.h"

namespace coinroll::pipeline {

// Kind: `Rhs` and `rhs()`, the right-hand side to integrate; `kContinuesAngles`, Motion's
// continuesAngles(); `sample(y, continuation)`, the RunSample of an integrated state y.
// Interface: Motion, or an interface derived from it (a HybridRun's segment).
template <int N, class Kind, class Interface = Motion>
class TrajectoryMotion : public Interface {
 public:
  TrajectoryMotion(Kind kind, double t0, const integrate::Vec<N>& y0, const integrate::SolverConfig& solver,
                   std::vector<integrate::Event<N>> events, double duration)
      : kind_(std::move(kind)), trajectory_(kind_.rhs(), t0, y0, solver, std::move(events)), duration_(duration) {}

  bool continuesAngles() const override { return Kind::kContinuesAngles; }

  std::optional<RunSample> sampleAt(double t, const physics::CoinState& continuation) override {
    const std::optional<integrate::Vec<N>> y = trajectory_.stateAt(t);
    if (!y) return std::nullopt;
    return kind_.sample(*y, continuation);
  }

  std::optional<RunEvent> stoppedBy(const physics::CoinState& continuation) const override {
    const auto& hit = trajectory_.stoppedBy();
    // A fixed step may end past the duration and find an event there: not this run's.
    if (!hit || hit->t > duration_) return std::nullopt;
    return runEventOf(hit->id, hit->t, kind_.sample(hit->y, continuation));
  }

  std::vector<RunEvent> warnings() const override {
    std::vector<RunEvent> crossings;
    for (const auto& hit : trajectory_.nonTerminalHits()) {
      if (hit.t > duration_) break;
      crossings.push_back(runEventOf(hit.id, hit.t, kind_.sample(hit.y, physics::CoinState{})));
    }
    return crossings;
  }

  integrate::Stats stats() const override { return trajectory_.stats(); }

 protected:
  const Kind& kind() const { return kind_; }
  const std::optional<integrate::EventHit<N>>& endHit() const { return trajectory_.stoppedBy(); }

 private:
  Kind kind_;
  integrate::Trajectory<N, typename Kind::Rhs> trajectory_;
  double duration_;  // s; events found past it (by a fixed step's overshoot) are not reported
};

}  // namespace coinroll::pipeline
