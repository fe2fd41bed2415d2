#pragma once
// What evolves: the seed's Euler angles, the angular velocity in the coin frame XYZ and the
// centre of mass on the floor. Eight numbers, nothing else (trace history lives elsewhere).

#include <Eigen/Core>

namespace coinroll::physics {

struct CoinState {
  double theta = 0;    // rad, tilt from vertical (0 = upright)
  double phi = 0;      // rad, heading (precession angle about the floor normal y)
  double psi = 0;      // rad, spin angle about the coin's symmetry axis Z
  double omega_X = 0;  // rad/s, angular velocity along e_X (horizontal, in the coin plane)
  double omega_Y = 0;  // rad/s, along e_Y (in the coin plane, upward)
  double omega_Z = 0;  // rad/s, along e_Z (coin normal)
  double x = 0;        // m, centre of mass on the floor plane
  double z = 0;        // m
};

inline constexpr int kStateSize = 8;
using StateVec = Eigen::Matrix<double, kStateSize, 1>;

// Index of each CoinState field in StateVec, in declaration order.
enum StateIndex : int { kTheta, kPhi, kPsi, kOmega_X, kOmega_Y, kOmega_Z, kX, kZ };

inline StateVec toVector(const CoinState& s) {
  StateVec y;
  y << s.theta, s.phi, s.psi, s.omega_X, s.omega_Y, s.omega_Z, s.x, s.z;
  return y;
}

inline CoinState toState(const StateVec& y) {
  return {y[kTheta], y[kPhi], y[kPsi], y[kOmega_X], y[kOmega_Y], y[kOmega_Z], y[kX], y[kZ]};
}

}  // namespace coinroll::physics
