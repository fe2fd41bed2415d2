#pragma once
// The seed's equations of motion in Euler angles, eqs. (14)-(19), for any axisymmetric coin.
// They are singular at theta = +-90 degrees (tan theta, 1 / cos theta): callers stop before
// that with the coin-flat event (validity.h).

#include "physics/coin_model.h"
#include "physics/coin_state.h"

namespace coinroll::physics {

// d(omega)/dt in the coin frame, eqs. (14)-(16).
struct AngularAcceleration {
  double dOmega_X = 0;  // rad/s^2
  double dOmega_Y = 0;  // rad/s^2
  double dOmega_Z = 0;  // rad/s^2
};

AngularAcceleration angularAcceleration(const CoinModel& model, const CoinState& state);

// dy/dt for y = (theta, phi, psi, omega_X, omega_Y, omega_Z, x, z): eqs. (14)-(19) and the
// centre-of-mass velocity of seed section 4. `t` is unused (the model is autonomous) but keeps
// the integrators' f(t, y) shape.
StateVec rhs(const CoinModel& model, double t, const StateVec& y);

}  // namespace coinroll::physics
