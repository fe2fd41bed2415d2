#pragma once
// One run of a Simulation in the formulation its scene chose, seen through the seed's CoinState:
// the CSV (and any other consumer of samples) need not know which equations are integrated.

#include <optional>
#include <variant>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "integrate/trajectory.h"
#include "physics/coin_state.h"
#include "physics/quaternion_dynamics.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// The quaternion formulation's right-hand side bound to one model.
struct QuaternionRhs {
  const physics::CoinModel* model;
  physics::QuaternionStateVec operator()(double t, const physics::QuaternionStateVec& y) const {
    return physics::quaternionRhs(*model, t, y);
  }
};

using QuaternionTrajectory = integrate::Trajectory<physics::kQuaternionStateSize, QuaternionRhs>;

// validityEvents() for the quaternion state: coin-flat at physics::kQuaternionFlatTilt instead of
// physics::kFlatTilt, lift-off and slip unchanged.
std::vector<integrate::Event<physics::kQuaternionStateSize>> quaternionValidityEvents(const physics::CoinModel& model,
                                                                                      std::optional<double> friction);

class CoinRun {
 public:
  // Starts at t = 0 with the validity events armed. `simulation` must outlive the run.
  explicit CoinRun(const Simulation& simulation);

  // The state at t >= every earlier query; std::nullopt once an event has ended the run before t.
  // phi and psi are continuous in t in both formulations.
  std::optional<physics::CoinState> stateAt(double t);

  // The event that ended the run, its state in the seed's variables.
  std::optional<integrate::EventHit<physics::kStateSize>> stoppedBy() const;

  integrate::Stats stats() const;

 private:
  std::optional<physics::CoinState> quaternionStateAt(QuaternionTrajectory& trajectory, double t);

  std::variant<CoinTrajectory, QuaternionTrajectory> trajectory_;
  double lastTime_ = 0;             // s, time of lastState_
  physics::CoinState lastState_;    // the latest sample: the continuation for phi and psi
};

}  // namespace coinroll::pipeline
