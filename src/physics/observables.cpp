#include "physics/observables.h"

#include <cmath>

#include "physics/dynamics.h"

namespace coinroll::physics {

Eigen::Matrix3d coinAxesInFloor(const CoinState& s) {
  const double st = std::sin(s.theta), ct = std::cos(s.theta);
  const double sp = std::sin(s.phi), cp = std::cos(s.phi);
  Eigen::Matrix3d R;
  R << cp, 0, -sp,            // e_X
      st * sp, ct, st * cp,   // e_Y
      ct * sp, -st, ct * cp;  // e_Z
  return R;
}

Eigen::Quaterniond attitude(const CoinState& s) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(s.phi, Eigen::Vector3d::UnitY())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(s.theta, Eigen::Vector3d::UnitX())) *
         Eigen::Quaterniond(Eigen::AngleAxisd(s.psi, Eigen::Vector3d::UnitZ()));
}

double energy(const CoinModel& m, const CoinState& s) {
  const double wX2 = s.omega_X * s.omega_X, wY2 = s.omega_Y * s.omega_Y, wZ2 = s.omega_Z * s.omega_Z;
  const double rotation = 0.5 * (m.I_X * (wX2 + wY2) + m.I_Z * wZ2);
  if (m.rim.thin()) {
    const double Ma2 = m.M * m.a * m.a;
    return 0.5 * Ma2 * (wX2 + wZ2) + rotation + m.M * m.g * m.a * std::cos(s.theta);
  }
  return 0.5 * m.M * centreOfMassVelocity(m, s).squaredNorm() + rotation + m.M * m.g * centreOfMass(m, s).y();  // (4.4)
}

Eigen::Vector3d centreOfMass(const CoinModel& m, const CoinState& s) {
  const double sinTheta = std::sin(s.theta), cosTheta = std::cos(s.theta);
  if (m.rim.thin()) return {s.x, m.a * cosTheta, s.z};
  return {s.x, centreHeight(contactOffset(m.rim, m.a, sinTheta, cosTheta), sinTheta, cosTheta), s.z};
}

Eigen::Vector3d contactVector(const CoinModel& m, const CoinState& s) {
  const Eigen::Matrix3d axes = coinAxesInFloor(s);
  if (m.rim.thin()) return -m.a * axes.row(1).transpose();
  const ContactOffset o = contactOffset(m.rim, m.a, std::sin(s.theta), std::cos(s.theta));
  return (-o.reach * axes.row(1) + o.lift * axes.row(2)).transpose();  // (1.3)
}

Eigen::Vector3d centreOfMassVelocity(const CoinModel& m, const CoinState& s) {
  const Eigen::Matrix3d axes = coinAxesInFloor(s);
  if (m.rim.thin()) {
    // v = a (-omega_Z e_X + omega_X e_Z), e_X and e_Z the rows of coinAxesInFloor.
    return m.a * (-s.omega_Z * axes.row(0) + s.omega_X * axes.row(2)).transpose();
  }
  const Eigen::Vector3d omega = axes.transpose() * Eigen::Vector3d(s.omega_X, s.omega_Y, s.omega_Z);
  return -omega.cross(contactVector(m, s));  // no slip at the material contact point (1.6)
}

Eigen::Vector3d contactPoint(const CoinModel& m, const CoinState& s) {
  if (m.rim.thin()) {
    // r_c = r - a e_Y.
    const Eigen::Vector3d eY = coinAxesInFloor(s).row(1).transpose();
    return centreOfMass(m, s) - m.a * eY;
  }
  return centreOfMass(m, s) + contactVector(m, s);
}

double spinRate(const CoinState& s) { return s.omega_Z + std::tan(s.theta) * s.omega_Y; }

double precessionRate(const CoinState& s) { return s.omega_Y / std::cos(s.theta); }

Reaction reaction(const CoinModel& m, const CoinState& s) { return forward(m, s).reaction; }

}  // namespace coinroll::physics
