#pragma once
// One run of a Simulation in the formulation its scene chose, seen through the seed's CoinState:
// the CSV (and any other consumer of samples) need not know which equations are integrated, nor
// whether the dissipated energy is integrated beside them.

#include <atomic>
#include <optional>
#include <variant>
#include <vector>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "integrate/trajectory.h"
#include "physics/coin_rhs.h"
#include "physics/coin_state.h"
#include "physics/forward.h"
#include "physics/validity.h"
#include "pipeline/hybrid_run.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// One sample of a run.
struct RunSample {
  physics::CoinState state;  // the seed's variables
  physics::Forward forward;  // the integrating formulation's forward pass at this state
  double dissipated = 0;     // J, energy the effects have dissipated since t = 0
};

class CoinRun {
 public:
  // Starts at t = 0 with the validity events armed. The run keeps its own copy of the model.
  explicit CoinRun(const Simulation& simulation);

  // The sample at t >= every earlier query; std::nullopt once an event has ended the run before
  // t. phi and psi are continuous in t in both formulations. Throws Cancelled when the
  // simulation's cancel flag is set.
  std::optional<RunSample> sampleAt(double t);
  std::optional<physics::CoinState> stateAt(double t);

  // The event that ended the run before its duration.
  std::optional<RunEvent> stoppedBy() const;

  // Lift-off and slip crossings the run went on past (on_invalid "warn"), in time order so far.
  std::vector<RunEvent> warnings() const;

  // The switches between rolling and sliding so far (none unless the scene has "sliding": true).
  std::vector<ModeSwitch> switches() const;

  integrate::Stats stats() const;

 private:
  template <physics::Formulation F, int N>
  using Run = integrate::Trajectory<N, physics::CoinRhs<F>>;
  using EulerRun = Run<physics::Formulation::EulerAngles, physics::kStateSize>;
  using EulerDissipativeRun = Run<physics::Formulation::EulerAngles, physics::kStateSize + 1>;
  using QuaternionRun = Run<physics::Formulation::Quaternion, physics::kQuaternionStateSize>;
  using QuaternionDissipativeRun = Run<physics::Formulation::Quaternion, physics::kQuaternionStateSize + 1>;

  template <physics::Formulation F, int N>
  std::optional<RunSample> sampleOf(Run<F, N>& run, double t);

  template <physics::Formulation F, int N>
  RunEvent eventOf(const integrate::EventHit<N>& hit, const physics::CoinState& continuation) const;

  std::optional<RunSample> hybridSampleAt(HybridRun& run, double t);

  // HybridRun: "sliding": true (rolling and sliding segments of the quaternion formulation).
  std::variant<EulerRun, EulerDissipativeRun, QuaternionRun, QuaternionDissipativeRun, HybridRun> trajectory_;
  double lastTime_ = 0;             // s, time of lastState_
  physics::CoinState lastState_;    // the latest sample: the continuation for phi and psi
  physics::Forward lastForward_;    // at lastTime_, once lastForwardValid_
  bool lastForwardValid_ = false;
  double lastDissipated_ = 0;       // J, at lastTime_
  physics::CoinModel model_;
  const std::atomic<bool>* cancel_ = nullptr;
  double duration_ = 0;             // s; events found past it (by a fixed step's overshoot) are not reported
};

}  // namespace coinroll::pipeline
