#pragma once
// The contact seen from the coin's material frame (docs/quaternion_formulation.md §2, docs/rim.md §3):
// what the attitude alone fixes, and how the contact vector moves. Shared by the rolling quaternion
// formulation and the sliding one (docs/sliding.md), which differ only in the contact force.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/forward.h"
#include "physics/rim.h"

namespace coinroll::physics {

struct ContactGeometry {
  Eigen::Matrix3d floorFromBody;  // columns: the material axes b1, b2, b3 in floor components
  Eigen::Vector3d up;             // e_y, the floor's upward normal
  Eigen::Vector3d e_X, e_Y;       // the seed's in-plane axes: e_Y points up the coin plane (eq. 2.1)
  double sinTheta = 0;            // -e_y . e_Z: positive when the e_Z face is the lower one
  double cosTheta = 0;            // |e_y minus its normal part|, = cos(theta) >= 0
  Eigen::Vector3d c;              // m, from the centre of mass to the contact point (eq. 2.2; rim.md eq. 3.1)
  ContactOffset offset;           // the rim's c = -reach e_Y + lift e_Z (unused for the thin coin)
};

ContactGeometry contactGeometry(const CoinModel& m, const Eigen::Quaterniond& unitQ);

// psi-dot = e_X . (e_y x omega) / cos(theta) is the one place 1 / cos(theta) remains; it is the
// physical rolling rate, finite along every finite-energy motion short of flat.
double spinRateOf(const ContactGeometry& geo, const Eigen::Vector3d& omega);

// dc/dt in material components: the contact point runs round the rim at psi-dot (eq. 2.4); with
// a rim, reach and lift also change with the tilt at theta-dot = omega . e_X (docs/rim.md eq. 3.2).
Eigen::Vector3d contactDrift(const CoinModel& m, const ContactGeometry& geo, const Eigen::Vector3d& omega);

// Fills what the attitude, the rates and the centre's velocity fix: theta, the axes, omega, the
// contact vector and point, the centre, psi-dot, phi-dot and the energy (the dynamics' fields are
// the caller's).
void setAttitudeKinematics(const CoinModel& m, const Eigen::Quaterniond& unitQ, const Eigen::Vector3d& omegaBody,
                           double x, double z, const ContactGeometry& geo, const Eigen::Vector3d& velocity, Forward& f);

}  // namespace coinroll::physics
