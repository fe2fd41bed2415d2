#pragma once
// Everything one state of the motion fixes, computed once by the formulation that integrates the
// run (MuJoCo's mj_forward): its right-hand side, the validity margins, the CSV row, the overlay,
// the trace, sweeps and the sound all read this struct, so a new contact geometry or contact force
// changes the formulation's forward pass and nothing downstream. Floor frame xyz, y up.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

#include "physics/contact_kinematics.h"

namespace coinroll::physics {

// The floor's reaction R = M dv/dt + M g e_y (the effects are couples and add no force), with its
// vertical part N and horizontal size F.
struct Reaction {
  Eigen::Vector3d R = Eigen::Vector3d::Zero();  // N, floor components
  double N = 0;                                 // N, normal force R_y (the model needs N > 0)
  double F = 0;                                 // N, friction force sqrt(R_x^2 + R_z^2) (docs/seed.md §4)
};

struct Forward {
  double theta = 0;  // rad, the seed's tilt from vertical, signed (positive: the e_Z face is the lower one)
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();       // rows: e_X, e_Y, e_Z in floor components
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();          // rad/s, floor components
  Eigen::Vector3d contactVector = Eigen::Vector3d::Zero();  // m, c: centre of mass to contact point
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();         // m, centre of mass
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();       // m/s, centre of mass
  Eigen::Vector3d contactPoint = Eigen::Vector3d::Zero();   // m, on the floor (y = 0 up to round-off)
  double spinRate = 0;                                      // rad/s, psi-dot: the contact point running round the rim
  double precessionRate = 0;                         // rad/s, phi-dot = Omega: the contact point going round the floor
  Eigen::Vector3d dOmega = Eigen::Vector3d::Zero();  // rad/s^2, in the formulation's own components
  Reaction reaction;                                 // with friction's part while sliding
  Loads loads;        // the effects' couple and dissipated power (and friction's mu N |s| while sliding)
  double energy = 0;  // J, kinetic plus potential
  // The contact (docs/sliding.md): the velocity of the coin's material point there (zero while
  // rolling), whether it slides, and while sliding the normal effective mass D of eq. 3.2, whose
  // sign decides whether the held contact has a unique normal force (Painleve: D <= 0).
  Eigen::Vector3d slip = Eigen::Vector3d::Zero();  // m/s, floor components, horizontal
  bool sliding = false;
  double normalEffectiveMass = 1;
  // In flight (docs/flight.md) there is no contact: the reaction and loads are zero and the contact
  // point is the rim's lowest point, above the floor.
  bool flying = false;
};

// alpha, rad: the coin plane's tilt above the floor, pi/2 - |theta|, from e_Y's rise and e_Z's, so it
// stays accurate near flat where pi/2 - |theta| would cancel.
inline double tiltAboveFloor(const Forward& f) { return std::atan2(f.axes(1, 1), std::abs(f.axes(2, 1))); }

// Whether Omega = phi-dot is a rate something goes round at: the coin's axis (e_Z) circles the
// vertical faster than it nods towards or away from it. A coin rocking through flat (falling_flat)
// whips its heading through tens of degrees in milliseconds, a phi-dot of kHz that nothing on the
// floor goes round at; an exactly flat axis has no heading at all.
inline bool axisGoesRound(const Forward& f) {
  const Eigen::Vector3d axis = f.axes.row(2).transpose();
  const Eigen::Vector3d azimuthal = Eigen::Vector3d::UnitY().cross(axis);  // |.| = sin(axis to vertical)
  if (azimuthal.norm() < 1e-12) return false;
  const Eigen::Vector3d around = azimuthal.normalized();
  const Eigen::Vector3d axisVelocity = f.omega.cross(axis);
  const double circling = axisVelocity.dot(around);
  const double nodding = (axisVelocity - circling * around).norm();
  return std::abs(circling) >= nodding;
}

}  // namespace coinroll::physics
