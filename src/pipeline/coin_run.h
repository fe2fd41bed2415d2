#pragma once
// One run of a Simulation in the formulation its scene chose, seen through the seed's CoinState:
// the CSV (and any other consumer of samples) need not know which equations are integrated, nor
// whether the dissipated energy is integrated beside them.

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "integrate/solver_config.h"
#include "physics/coin_state.h"
#include "pipeline/motion.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

class CoinRun {
 public:
  // Starts at t = 0 with the validity events armed. The run keeps its own copy of the model.
  explicit CoinRun(const Simulation& simulation);

  // The sample at t >= every earlier query; std::nullopt once an event has ended the run before
  // t. phi and psi are continuous in t in every formulation. Throws Cancelled when the
  // simulation's cancel flag is set.
  std::optional<RunSample> sampleAt(double t);
  std::optional<physics::CoinState> stateAt(double t);

  // The event that ended the run before its duration.
  std::optional<RunEvent> stoppedBy() const;

  // Lift-off and slip crossings the run went on past (on_invalid "warn"), in time order so far.
  std::vector<RunEvent> warnings() const;

  // The switches between rolling and sliding so far (none unless the scene has "sliding": true); a run
  // that starts off the rolling constraint (an initial slip, or the static cone exceeded) has one at t = 0.
  std::vector<ModeSwitch> switches() const;

  // The rim's impacts so far (none unless the scene has "flight": true).
  std::vector<ImpactRecord> impacts() const;

  integrate::Stats stats() const;

 private:
  // The formulation's run, or a HybridRun for "sliding": true (rolling and sliding segments).
  std::unique_ptr<Motion> motion_;
  double lastTime_ = 0;   // s, time of last_
  RunSample last_;        // the latest sample: its state is the continuation for phi and psi
  bool sampled_ = false;  // whether last_ is a sample yet (else its state is the initial one)
  const std::atomic<bool>* cancel_ = nullptr;
};

}  // namespace coinroll::pipeline
