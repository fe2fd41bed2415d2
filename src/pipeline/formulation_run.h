#pragma once
// A run that integrates one formulation's equations throughout ("sliding" off), with the dissipated
// energy beside them when effects are on. Each formulation is compiled in its own file
// (euler_angles_run.cpp, quaternion_run.cpp: the explicit instantiations below), so no translation
// unit instantiates the integrator for every state.

#include <memory>

#include "integrate/solver_config.h"
#include "physics/coin_model.h"
#include "physics/coin_rhs.h"
#include "physics/coin_state.h"
#include "physics/formulation.h"
#include "pipeline/motion.h"
#include "pipeline/simulation.h"
#include "pipeline/trajectory_motion.h"
#include "pipeline/validity_events.h"

namespace coinroll::pipeline {

// A state of formulation F with N components, the dissipated energy last when N exceeds the
// formulation's own size, read in the seed's variables (TrajectoryMotion's Kind).
template <physics::Formulation F, int N>
struct FormulationKind {
  using Rhs = physics::CoinRhs<F>;
  static constexpr bool kContinuesAngles = F == physics::Formulation::Quaternion;
  static constexpr bool kDissipative = N > physics::kMotionSize<F>;

  physics::CoinModel model;

  Rhs rhs() const { return Rhs{model}; }
  RunSample sample(const integrate::Vec<N>& y, const physics::CoinState& continuation) const {
    return {.state = seedState<F, N>(y, continuation),
            .forward = forwardOf<F, N>(model, y),
            .dissipated = kDissipative ? y[N - 1] : 0};
  }
};

template <physics::Formulation F, int N>
using FormulationRun = TrajectoryMotion<N, FormulationKind<F, N>>;

// Starts simulation's run in formulation F at t = 0 with the validity events armed.
template <physics::Formulation F>
std::unique_ptr<Motion> startFormulationRun(const Simulation& simulation) {
  const auto start = [&simulation]<int N>() -> std::unique_ptr<Motion> {
    integrate::Vec<N> y0;
    if constexpr (F == physics::Formulation::EulerAngles) {
      y0.template head<physics::kStateSize>() = physics::toVector(simulation.initial);
    } else {
      y0.template head<physics::kQuaternionStateSize>() =
          physics::toVector(physics::fromEulerState(simulation.initial));
    }
    if constexpr (FormulationKind<F, N>::kDissipative) y0[N - 1] = 0;  // nothing dissipated yet
    return std::make_unique<FormulationRun<F, N>>(
        FormulationKind<F, N>{simulation.model}, 0.0, y0, simulation.solver,
        validityEvents<F, N>(simulation.model, simulation.model.friction.cone, simulation.validityIsTerminal,
                             remembering<N>([model = simulation.model](const integrate::Vec<N>& y) {
                               return forwardOf<F, N>(model, y);
                             })),
        simulation.duration);
  };
  constexpr int kSize = physics::kMotionSize<F>;
  if (!simulation.model.effects.empty()) return start.template operator()<kSize + 1>();
  return start.template operator()<kSize>();
}

extern template std::unique_ptr<Motion> startFormulationRun<physics::Formulation::EulerAngles>(const Simulation&);
extern template std::unique_ptr<Motion> startFormulationRun<physics::Formulation::Quaternion>(const Simulation&);

}  // namespace coinroll::pipeline
