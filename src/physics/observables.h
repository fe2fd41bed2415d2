#pragma once
// Quantities derived from one state (seed section 4): energy, positions and velocities, the
// floor's reaction, the attitude quaternion. Floor frame xyz has y up; the floor is y = 0.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/dynamics.h"

namespace coinroll::physics {

// Rows are e_X, e_Y, e_Z in floor components: R(theta, phi) of seed eq. (7).
Eigen::Matrix3d coinAxesInFloor(const CoinState& state);

// Active rotation taking the body's axes to the floor frame, q = q_y(phi) q_x(theta) q_z(psi)
// (ERRATA, "Conventions"). For psi = 0 it maps e_x, e_y, e_z onto the rows of R(theta, phi).
Eigen::Quaterniond attitude(const CoinState& state);

// Total mechanical energy, J: kinetic (translation + rotation) plus potential M g a cos(theta).
double energy(const CoinModel& model, const CoinState& state);

// Centre of mass, m: (x, a cos theta, z).
Eigen::Vector3d centreOfMass(const CoinModel& model, const CoinState& state);

// Centre-of-mass velocity, m/s, from the no-slip condition v = a (-omega_Z e_X + omega_X e_Z).
Eigen::Vector3d centreOfMassVelocity(const CoinModel& model, const CoinState& state);

// The point of the rim touching the floor, m (y = 0 up to round-off).
Eigen::Vector3d contactPoint(const CoinModel& model, const CoinState& state);

// psi-dot, rad/s: the rate at which the rim rolls over the floor (eq. 19). The contact point
// moves at speed a |psi-dot|.
double spinRate(const CoinState& state);

// phi-dot, rad/s: rate of change of heading (eq. 18).
double precessionRate(const CoinState& state);

// The floor's reaction with its normal force N and friction force F, including the effects'
// couples: dynamics(model, state).reaction.
Reaction reaction(const CoinModel& model, const CoinState& state);

}  // namespace coinroll::physics
