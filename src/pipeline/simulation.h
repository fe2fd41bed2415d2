#pragma once
// A scene turned into what the integrator needs: the coin model with its effects, its initial
// state, the solver and how the validity events act. Shared by `simulate`, `still` and `render`.

#include <atomic>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/flight.h"
#include "physics/formulation.h"
#include "pipeline/run_event.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

struct Simulation {
  physics::CoinModel model;  // with the scene's effects and friction
  physics::CoinState initial;
  integrate::SolverConfig solver;
  physics::Formulation formulation = physics::Formulation::EulerAngles;  // which equations CoinRun integrates
  // "sliding": the coin slides with Coulomb friction model.friction.kinetic instead of stopping at
  // slip (pipeline/hybrid_run.h); the quaternion formulation carries it.
  bool sliding = false;
  std::optional<Eigen::Vector2d> initialVelocity;  // m/s, (v_x, v_z); none: the rolling velocity
  // "flight": lift-off goes on in flight and the rim's impacts follow model.impact (docs/flight.md);
  // false: lift-off ends a sliding run.
  bool flight = false;
  bool stopWhenDecided = false;                   // flight: end at the event decided (docs/flight.md §5a)
  std::optional<double> initialHeight;            // m, initial.y: the centre's height (flight only); none: on the floor
  std::optional<double> initialVerticalVelocity;  // m/s, initial.v_y (flight only)
  bool validityIsTerminal = true;                 // on_invalid: "stop" ends the run at lift-off or slip
  double duration = 0;                            // s
  // When set and true, runs of this simulation stop at their next sample with Cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

// Builds the model (disk, ring or custom inertia, effects), resolves a steady-state `initial` for
// that model and maps the solver block. Throws scene::SceneError naming the key for combinations
// only physics can judge (e.g. the f- circle at theta = 0).
Simulation buildSimulation(const scene::SceneConfig& scene);

// Where a run with flight starts (docs/flight.md): in the air, when its rim is above the floor or
// moving up from it or the floor cannot hold it (N <= 0); std::nullopt: on the floor.
std::optional<physics::FlightState> flightStart(const Simulation& simulation);

// A note for scenes whose `initial` names a steady state of the ideal model while effects are on:
// the state is only where the spin-down starts. Empty otherwise.
std::string steadyStartNote(const scene::SceneConfig& scene);

// "coin-flat at t = 1.234567 s (theta = 89.0 deg): ..."-style description of why a run stopped
// or where the model was left.
std::string describeStop(const RunEvent& hit);

}  // namespace coinroll::pipeline
