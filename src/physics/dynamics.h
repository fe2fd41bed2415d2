#pragma once
// The Euler-angle formulation: the seed's equations (14)-(19) for any axisymmetric thin coin, and
// for a coin with a rim (thickness, edge radius) their generalisation in the same frame XYZ
// (docs/rim.md §2), with the couples of the model's effects added (docs/euler_disk.md §1). They are
// singular at theta = +-90 degrees (tan theta, 1 / cos theta): callers stop before that with the
// coin-flat event (validity.h).

#include <Eigen/Core>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/contact_kinematics.h"
#include "physics/forward.h"

namespace coinroll::physics {

// The forward pass of this formulation at one state; Forward::dOmega is d(omega)/dt in XYZ.
Forward forward(const CoinModel& model, const CoinState& state);

// The contact kinematics the effects read, at a given normal force N.
ContactKinematics contactKinematics(const CoinModel& model, const CoinState& state, double N);

// dy/dt and the power the effects dissipate, W.
struct Rates {
  StateVec dy;
  double power = 0;
};

Rates rates(const CoinModel& model, const StateVec& y);

// dy/dt for y = (theta, phi, psi, omega_X, omega_Y, omega_Z, x, z): eqs. (14)-(19) and the
// centre-of-mass velocity of seed section 4 (docs/rim.md eqs. 2.4-2.6 with a rim). `t` is unused
// (the model is autonomous) but keeps the integrators' f(t, y) shape.
StateVec rhs(const CoinModel& model, double t, const StateVec& y);

}  // namespace coinroll::physics
