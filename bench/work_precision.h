#pragma once
// Shared by the work-precision benchmark's drivers: the cases, the one right-hand side every
// solver calls, and what one run reports.

#include <chrono>
#include <string>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/coin_rhs.h"
#include "physics/dynamics.h"
#include "physics/observables.h"

namespace coinroll::bench {

// The seed's equations bound to one model, counting its calls; every solver, ours and the peers,
// calls this same object (the peers through thin adapters that only copy eight doubles in and out).
struct CoinRhs {
  physics::CoinRhs<physics::Formulation::EulerAngles> seed;
  long* evaluations;  // counts every call, so all solvers are counted the same way
  physics::StateVec operator()(double t, const physics::StateVec& y) const {
    ++*evaluations;
    return seed(t, y);
  }
};

struct Case {
  std::string name;
  physics::CoinModel model;
  physics::CoinState start;
  double tEnd = 0;  // s
};

// What one solver run reports. `maxEnergyError` is relative and sampled at the end of every step.
struct RunResult {
  physics::StateVec yEnd = physics::StateVec::Zero();
  long rhsEvaluations = 0;
  long steps = 0;
  long rejectedSteps = 0;
  double maxEnergyError = 0;
  bool failed = false;  // the solver gave up or produced a non-finite state
};

// Relative energy error of y against the case's start.
inline double energyError(const Case& c, const physics::StateVec& y) {
  const double E0 = physics::energy(c.model, c.start);
  return std::abs(physics::energy(c.model, physics::toState(y)) - E0) / std::abs(E0);
}

// A peer solver at one tolerance. `trackEnergy` asks for the energy error at every step (an
// untimed run); timed runs leave it off so observers cost nothing.
using PeerRun = RunResult (*)(const Case& c, double tolerance, bool trackEnergy);

RunResult boostDopri5(const Case& c, double tolerance, bool trackEnergy);
RunResult boostFehlberg78(const Case& c, double tolerance, bool trackEnergy);
RunResult boostBulirschStoer(const Case& c, double tolerance, bool trackEnergy);
RunResult cvodeAdams(const Case& c, double tolerance, bool trackEnergy);

}  // namespace coinroll::bench
