#include "physics/observables.h"

#include <cmath>

#include "physics/dynamics.h"

namespace coinroll::physics {

Eigen::Matrix3d coinAxesInFloor(const CoinState& s) {
  const double st = std::sin(s.theta), ct = std::cos(s.theta);
  const double sp = std::sin(s.phi), cp = std::cos(s.phi);
  Eigen::Matrix3d R;
  R << cp,      0,   -sp,       // e_X
       st * sp, ct,  st * cp,   // e_Y
       ct * sp, -st, ct * cp;   // e_Z
  return R;
}

Eigen::Quaterniond attitude(const CoinState& s) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(s.phi, Eigen::Vector3d::UnitY())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(s.theta, Eigen::Vector3d::UnitX())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(s.psi, Eigen::Vector3d::UnitZ()));
}

double energy(const CoinModel& m, const CoinState& s) {
  const double Ma2 = m.M * m.a * m.a;
  const double wX2 = s.omega_X * s.omega_X, wY2 = s.omega_Y * s.omega_Y, wZ2 = s.omega_Z * s.omega_Z;
  return 0.5 * Ma2 * (wX2 + wZ2) + 0.5 * (m.I_X * (wX2 + wY2) + m.I_Z * wZ2) +
         m.M * m.g * m.a * std::cos(s.theta);
}

Eigen::Vector3d centreOfMass(const CoinModel& m, const CoinState& s) {
  return {s.x, m.a * std::cos(s.theta), s.z};
}

Eigen::Vector3d centreOfMassVelocity(const CoinModel& m, const CoinState& s) {
  // v = a (-omega_Z e_X + omega_X e_Z), e_X and e_Z the rows of coinAxesInFloor.
  const Eigen::Matrix3d axes = coinAxesInFloor(s);
  const Eigen::Vector3d v = m.a * (-s.omega_Z * axes.row(0) + s.omega_X * axes.row(2)).transpose();
  return v;
}

Eigen::Vector3d contactPoint(const CoinModel& m, const CoinState& s) {
  // r_c = r - a e_Y.
  const Eigen::Vector3d eY = coinAxesInFloor(s).row(1).transpose();
  return centreOfMass(m, s) - m.a * eY;
}

double spinRate(const CoinState& s) { return s.omega_Z + std::tan(s.theta) * s.omega_Y; }

double precessionRate(const CoinState& s) { return s.omega_Y / std::cos(s.theta); }

Reaction reaction(const CoinModel& m, const CoinState& s) { return dynamics(m, s).reaction; }

}  // namespace coinroll::physics
