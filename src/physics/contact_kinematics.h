#pragma once
// What a dissipation law may read of the motion, in floor components and free of any
// formulation's coordinates, so that one law serves the Euler angles and the quaternion alike
// (docs/euler_disk.md §1). Floor frame xyz with y up.

#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace coinroll::physics {

struct ContactKinematics {
  Eigen::Vector3d e_X;    // coin axis: horizontal, in the coin plane, along the rim at the contact
  Eigen::Vector3d e_Y;    // coin axis: in the coin plane, from the contact point towards the centre
  Eigen::Vector3d e_Z;    // coin axis: the face normal
  Eigen::Vector3d omega;  // rad/s, angular velocity
  double faceRadius = 0;  // m, radius of the flat face the air gap lies under: a - rho (docs/rim.md §6)
  // m, a: the floor's pressure on the coin centres no farther than this from P; infinite, no bound.
  double outerRadius = std::numeric_limits<double>::infinity();
  double holeRadius = 0;  // m, a ring's hole b <= faceRadius in that face: no air is squeezed under it
  double N = 0;           // N, normal force of the floor (the model needs N > 0)
};

// The floor's upward normal e_y.
inline Eigen::Vector3d floorNormal() { return Eigen::Vector3d::UnitY(); }

// alpha, rad: the coin plane's tilt above the floor, pi/2 - |theta|, in [0, pi/2]. From e_Y's rise
// and e_Z's, so it stays accurate near flat where asin(cos theta) would not.
inline double tiltAboveFloor(const ContactKinematics& k) { return std::atan2(k.e_Y.y(), std::abs(k.e_Z.y())); }

// h = e_X x e_y: unit, horizontal, perpendicular to the contact's travel over the floor; the axis
// the coin rolls about (docs/euler_disk.md eq. 2.9). omega . h = psi-dot cos(theta).
inline Eigen::Vector3d rollingAxis(const ContactKinematics& k) { return k.e_X.cross(floorNormal()); }

// omega_h, rad/s: the horizontal part of omega, the rocking of the face that pumps the air gap.
inline Eigen::Vector3d horizontalAngularVelocity(const ContactKinematics& k) {
  return k.omega - k.omega.dot(floorNormal()) * floorNormal();
}

// What a law does to the coin: a couple (the same torque about every point, so it adds no force
// and the no-slip contact reaction absorbs nothing) and the power it dissipates.
struct Loads {
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // N m, floor components
  double power = 0;  // W, dissipated, >= 0; equals -torque . omega (tested for every law)
};

inline Loads& operator+=(Loads& sum, const Loads& more) {
  sum.torque += more.torque;
  sum.power += more.power;
  return sum;
}

// x / sqrt(x^2 + scale^2): sign(x) for |x| >> scale, linear through 0. A Coulomb-type couple
// switches sign with its rate; the smooth ramp keeps the right-hand side differentiable for the
// integrators and makes the law viscous only for |x| below `scale`. sqrt, not std::hypot: the
// rates and scales here are far from overflow, and glibc's correctly rounded hypot took 7 % of a toss
// sweep's time.
inline double smoothSign(double x, double scale) { return x / std::sqrt(x * x + scale * scale); }

}  // namespace coinroll::physics
