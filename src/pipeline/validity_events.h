#pragma once
// The events that end the rolling model's validity, written once for both formulations and for
// states with or without the dissipated-energy component: each reads the integrated vector as the
// seed's CoinState and asks physics/validity.h.

#include <optional>
#include <vector>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "physics/coin_model.h"
#include "physics/coin_rhs.h"
#include "physics/coin_state.h"
#include "physics/formulation.h"
#include "physics/quaternion_dynamics.h"
#include "physics/validity.h"

namespace coinroll::pipeline {

// The seed's variables of an integrated state y of formulation F (its first kMotionSize<F>
// components). The quaternion carries no phi or psi: they are taken within pi of `continuation`'s.
template <physics::Formulation F, int N>
physics::CoinState seedState(const integrate::Vec<N>& y, const physics::CoinState& continuation = {}) {
  if constexpr (F == physics::Formulation::EulerAngles) {
    return physics::toState(y.template head<physics::kStateSize>());
  } else {
    return physics::toEulerState(physics::toQuaternionState(y.template head<physics::kQuaternionStateSize>()),
                                 continuation);
  }
}

// coin-flat (|theta| reaches physics::flatTiltFor), lift-off (N falls through 0) and, when mu is
// given, slip (F rises through mu N). coin-flat always ends the run; lift-off and slip end it
// when `validityIsTerminal`, else they are recorded and the run goes on.
template <physics::Formulation F, int N>
std::vector<integrate::Event<N>> validityEvents(const physics::CoinModel& model, std::optional<double> friction,
                                                bool validityIsTerminal) {
  using Y = integrate::Vec<N>;
  const double flatTilt = physics::flatTiltFor(model, F == physics::Formulation::Quaternion);
  std::vector<integrate::Event<N>> events;
  events.push_back({.name = "coin-flat",
                    .g = [flatTilt](double, const Y& y) { return physics::flatMargin(seedState<F, N>(y), flatTilt); },
                    .direction = -1});
  events.push_back({.name = "lift-off",
                    .g = [model](double, const Y& y) { return physics::liftOffMargin(model, seedState<F, N>(y)); },
                    .direction = -1,
                    .terminal = validityIsTerminal});
  if (friction) {
    events.push_back({.name = "slip",
                      .g = [model, mu = *friction](double, const Y& y) {
                        return physics::slipMargin(model, seedState<F, N>(y), mu);
                      },
                      .direction = -1,
                      .terminal = validityIsTerminal});
  }
  return events;
}

}  // namespace coinroll::pipeline
