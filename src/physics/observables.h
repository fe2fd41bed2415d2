#pragma once
// Quantities derived from one state in the seed's variables (seed section 4): energy, positions
// and velocities, the attitude quaternion, for the thin coin and for a coin with a rim (docs/rim.md
// §1, §4). Floor frame xyz has y up; the floor is y = 0. A run reads them through its formulation's
// forward pass (forward.h); these serve the Euler-angle one, steady states and the command line.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/forward.h"

namespace coinroll::physics {

// Rows are e_X, e_Y, e_Z in floor components: R(theta, phi) of seed eq. (7).
Eigen::Matrix3d coinAxesInFloor(const CoinState& state);

// Active rotation taking the body's axes to the floor frame, q = q_y(phi) q_x(theta) q_z(psi)
// (docs/seed.md §2). For psi = 0 it maps e_x, e_y, e_z onto the rows of R(theta, phi).
Eigen::Quaterniond attitude(const CoinState& state);

// Total mechanical energy, J: kinetic (translation + rotation) plus potential M g y_G.
double energy(const CoinModel& model, const CoinState& state);

// Centre of mass, m: (x, a cos theta, z) for the thin coin; the rim's height (docs/rim.md eq. 1.4).
Eigen::Vector3d centreOfMass(const CoinModel& model, const CoinState& state);

// c, m: from the centre of mass to the contact point, floor components (docs/rim.md eq. 1.3).
Eigen::Vector3d contactVector(const CoinModel& model, const CoinState& state);

// Centre-of-mass velocity, m/s, from the no-slip condition v = -omega x c
// (thin coin: v = a (-omega_Z e_X + omega_X e_Z)).
Eigen::Vector3d centreOfMassVelocity(const CoinModel& model, const CoinState& state);

// The point of the rim touching the floor, m (y = 0 up to round-off).
Eigen::Vector3d contactPoint(const CoinModel& model, const CoinState& state);

// psi-dot, rad/s: the rate at which the contact point runs round the rim (eq. 19).
double spinRate(const CoinState& state);

// phi-dot, rad/s: rate of change of heading (eq. 18).
double precessionRate(const CoinState& state);

// The floor's reaction with its normal force N and friction force F, including the effects'
// couples: forward(model, state).reaction.
Reaction reaction(const CoinModel& model, const CoinState& state);

}  // namespace coinroll::physics
