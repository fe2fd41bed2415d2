#pragma once
// A scene turned into what the integrator needs: the coin model, its initial state, the solver
// and the events that end the ideal model's validity. Shared by `simulate`, `still` and `render`.

#include <optional>
#include <string>
#include <vector>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "integrate/trajectory.h"
#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/dynamics.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

struct Simulation {
  physics::CoinModel model;
  physics::CoinState initial;
  integrate::SolverConfig solver;
  scene::Formulation formulation = scene::Formulation::EulerAngles;  // which equations CoinRun integrates
  std::optional<double> friction;  // mu; no slip monitor when absent
  double duration = 0;             // s
};

// Builds the model (disk, ring or custom inertia), resolves a steady-state `initial` for that
// model and maps the solver block. Throws scene::SceneError naming the key for combinations only
// physics can judge (e.g. the f- circle at theta = 0).
Simulation buildSimulation(const scene::SceneConfig& scene);

// The events that end the ideal rolling model: coin-flat (theta reaches physics::kFlatTilt),
// lift-off (N falls through 0) and, when mu is given, slip (|F| rises through mu N).
std::vector<integrate::Event<physics::kStateSize>> validityEvents(const physics::CoinModel& model,
                                                                  std::optional<double> friction);

// The seed's right-hand side bound to one model, as the integrators want it.
struct CoinRhs {
  const physics::CoinModel* model;
  physics::StateVec operator()(double t, const physics::StateVec& y) const { return physics::rhs(*model, t, y); }
};

using CoinTrajectory = integrate::Trajectory<physics::kStateSize, CoinRhs>;

// A trajectory of the Euler-angle formulation from t = 0 with the validity events armed, whatever
// simulation.formulation says (CoinRun honours it). `simulation` must outlive it.
CoinTrajectory startTrajectory(const Simulation& simulation);

// "coin-flat at t = 1.234567 s (theta = 89.0 deg)"-style description of why a run stopped.
std::string describeStop(const integrate::EventHit<physics::kStateSize>& hit);

}  // namespace coinroll::pipeline
