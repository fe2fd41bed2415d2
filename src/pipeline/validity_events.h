#pragma once
// The events that end the model's validity, written once for both formulations and for states
// with or without the dissipated-energy component: each reads the forward pass of the formulation
// that integrates the run (physics/forward.h) and asks physics/validity.h.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "physics/coin_model.h"
#include "physics/coin_rhs.h"
#include "physics/coin_state.h"
#include "physics/contact_mode.h"
#include "physics/dynamics.h"
#include "physics/formulation.h"
#include "physics/quaternion_dynamics.h"
#include "physics/validity.h"
#include "pipeline/motion.h"

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

// The forward pass of formulation F at an integrated state y.
template <physics::Formulation F, int N>
physics::Forward forwardOf(const physics::CoinModel& model, const integrate::Vec<N>& y) {
  if constexpr (F == physics::Formulation::EulerAngles) {
    return physics::forward(model, physics::toState(y.template head<physics::kStateSize>()));
  } else {
    return physics::forward(model, physics::toQuaternionState(y.template head<physics::kQuaternionStateSize>()));
  }
}

// The friction cone is read at this many points inside each step as well as at its ends: a wobble
// grazes it for a fraction of a step (F/N reached 0.24041 in a cone of 0.24 between two step ends
// inside it; docs/sliding.md §4.5), and a missed crossing is a slide the run never makes.
inline constexpr int kConeGrazeChecks = 3;

// A forward pass that remembers the last few states it was asked for, shared by the copies of the
// function (the events of one segment): a step's events read the same states one after another (its
// end, and lift-off's and the cone's checks at the same interior points), each a whole forward pass.
// A pure function's memo, keyed on y's bits: the results do not change.
template <int N>
std::function<physics::Forward(const integrate::Vec<N>&)> remembering(
    std::function<physics::Forward(const integrate::Vec<N>&)> forward) {
  constexpr std::size_t kStates = kConeGrazeChecks + 1;  // a step's interior points and its end
  struct Memo {
    std::array<integrate::Vec<N>, kStates> states;
    std::array<physics::Forward, kStates> passes;
    std::size_t filled = 0, next = 0;
  };
  return [forward = std::move(forward), memo = std::make_shared<Memo>()](const integrate::Vec<N>& y) {
    for (std::size_t i = 0; i < memo->filled; ++i) {
      if (std::memcmp(memo->states[i].data(), y.data(), sizeof(double) * N) == 0) return memo->passes[i];
    }
    memo->states[memo->next] = y;
    memo->passes[memo->next] = forward(y);
    const physics::Forward& pass = memo->passes[memo->next];
    memo->filled = std::max(memo->filled, memo->next + 1);
    memo->next = (memo->next + 1) % kStates;
    return pass;
  };
}

// theta alone, without a whole forward pass: the flat and corner events need nothing else.
template <physics::Formulation F, int N>
double thetaOf(const integrate::Vec<N>& y) {
  if constexpr (F == physics::Formulation::EulerAngles) {
    return y[physics::kTheta];
  } else {
    return physics::thetaOf(physics::toQuaternionState(y.template head<physics::kQuaternionStateSize>()).q);
  }
}

template <int N>
integrate::Event<N> modelEvent(physics::ModelEvent kind, std::function<double(double, const integrate::Vec<N>&)> g,
                               int direction, bool terminal) {
  return {.name = std::string(physics::eventName(kind)),
          .id = static_cast<int>(kind),
          .g = std::move(g),
          .direction = direction,
          .terminal = terminal};
}

template <physics::Formulation F, int N>
double tiltRateOf(const integrate::Vec<N>& y) {
  if constexpr (F == physics::Formulation::EulerAngles) {
    return y[physics::kOmega_X];
  } else {
    const physics::QuaternionState s = physics::toQuaternionState(y.template head<physics::kQuaternionStateSize>());
    return physics::tiltRate(s.q, s.omegaBody);
  }
}

// A chain's transition between contact modes (physics::Transition) as a terminal event, its id past
// ModelEvent's values (switchId).
template <int N>
integrate::Event<N> transitionEvent(physics::Transition transition,
                                    std::function<double(double, const integrate::Vec<N>&)> g, int direction = -1) {
  return {.name = std::string(physics::transitionName(transition)),
          .id = switchId(transition),
          .g = std::move(g),
          .direction = direction,
          .terminal = true};
}

// coin-flat or face-down (|theta| reaches physics::flatStopFor) and, for a rim with corners, theta
// passing 0: the events of the coin's geometry. The corner's crossing ends the run (corner-switch)
// unless `landsTheOtherCorner`: a chain with flight lands that corner there (Transition::CornerLands).
// `theta` reads the tilt of an integrated state, `tiltRate` its rate's sign (tiltRateOf): a corner
// rolled past upright and back within one step is seen at the turn of the tilt (docs/flight.md §4a).
template <int N>
std::vector<integrate::Event<N>> geometryEvents(const physics::CoinModel& model, physics::Formulation formulation,
                                                std::function<double(const integrate::Vec<N>&)> theta,
                                                std::function<double(const integrate::Vec<N>&)> tiltRate,
                                                bool landsTheOtherCorner = false) {
  using Y = integrate::Vec<N>;
  const physics::FlatStop flat = physics::flatStopFor(model, formulation);
  std::vector<integrate::Event<N>> events;
  events.push_back(modelEvent<N>(
      flat.event, [theta, tilt = flat.tilt](double, const Y& y) { return physics::flatMargin(theta(y), tilt); }, -1,
      true));
  if (physics::hasCorners(model)) {
    const auto upright = [theta](double, const Y& y) { return theta(y); };
    integrate::Event<N> corner = landsTheOtherCorner
                                     ? transitionEvent<N>(physics::Transition::CornerLands, upright, 0)
                                     : modelEvent<N>(physics::ModelEvent::CornerSwitch, upright, 0, true);
    corner.rate = [tiltRate](double, const Y& y) { return tiltRate(y); };
    events.push_back(std::move(corner));
  }
  return events;
}

// The geometry's events, lift-off (N falls through 0) and, when mu is given, slip (F rises through
// mu N). Lift-off and slip end the run when `validityIsTerminal`, else they are recorded and the run
// goes on. `forward` is formulation F's forward pass (a segment passes the one its other events share).
template <physics::Formulation F, int N>
std::vector<integrate::Event<N>> validityEvents(const physics::CoinModel& model, std::optional<double> friction,
                                                bool validityIsTerminal,
                                                std::function<physics::Forward(const integrate::Vec<N>&)> forward) {
  using Y = integrate::Vec<N>;
  using physics::ModelEvent;
  std::vector<integrate::Event<N>> events = geometryEvents<N>(
      model, F, [](const Y& y) { return thetaOf<F, N>(y); }, [](const Y& y) { return tiltRateOf<F, N>(y); });
  events.push_back(modelEvent<N>(
      ModelEvent::LiftOff, [model, forward](double, const Y& y) { return physics::liftOffMargin(model, forward(y)); },
      -1, validityIsTerminal));
  if (friction) {
    integrate::Event<N> slip = modelEvent<N>(
        ModelEvent::Slip,
        [model, forward, mu = *friction](double, const Y& y) { return physics::slipMargin(model, forward(y), mu); }, -1,
        validityIsTerminal);
    slip.interiorChecks = kConeGrazeChecks;
    events.push_back(std::move(slip));
  }
  return events;
}

}  // namespace coinroll::pipeline
