#pragma once
// The seed's equations of motion in Euler angles, eqs. (14)-(19), for any axisymmetric coin, with
// the couples of the model's effects added (docs/euler_disk.md §1). They are singular at
// theta = +-90 degrees (tan theta, 1 / cos theta): callers stop before that with the coin-flat
// event (validity.h).

#include <Eigen/Core>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/contact_kinematics.h"

namespace coinroll::physics {

// d(omega)/dt in the coin frame, eqs. (14)-(16).
struct AngularAcceleration {
  double dOmega_X = 0;  // rad/s^2
  double dOmega_Y = 0;  // rad/s^2
  double dOmega_Z = 0;  // rad/s^2
};

// The floor's reaction R = M dv/dt + M g e_y (the effects are couples and add no force), with its
// vertical part N and horizontal size F.
struct Reaction {
  Eigen::Vector3d R = Eigen::Vector3d::Zero();  // N, floor components
  double N = 0;                                 // N, normal force R_y (the model needs N > 0)
  double F = 0;                                 // N, friction force sqrt(R_x^2 + R_z^2) (ERRATA)
};

// Everything the equations give at one state.
struct Dynamics {
  AngularAcceleration dOmega;
  Reaction reaction;
  Loads loads;  // the effects' couple and dissipated power; zero without effects
};

Dynamics dynamics(const CoinModel& model, const CoinState& state);

// The contact kinematics the effects read, at a given normal force N.
ContactKinematics contactKinematics(const CoinModel& model, const CoinState& state, double N);

// dy/dt and the power the effects dissipate, W.
struct Rates {
  StateVec dy;
  double power = 0;
};

Rates rates(const CoinModel& model, const StateVec& y);

// dy/dt for y = (theta, phi, psi, omega_X, omega_Y, omega_Z, x, z): eqs. (14)-(19) and the
// centre-of-mass velocity of seed section 4. `t` is unused (the model is autonomous) but keeps
// the integrators' f(t, y) shape.
StateVec rhs(const CoinModel& model, double t, const StateVec& y);

}  // namespace coinroll::physics
