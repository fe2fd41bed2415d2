#include "physics/air_drag.h"

#include <cmath>
#include <numbers>

namespace coinroll::physics {

Loads loads(const AirDrag& law, const ContactKinematics& k) {
  const Eigen::Vector3d rocking = horizontalAngularVelocity(k);
  const double alpha = tiltAboveFloor(k);
  const double a = k.faceRadius, mu = law.viscosity;
  // Moffatt's P = pi mu a^3 Omega^2 / (4 alpha) with Omega = |omega_h| / alpha (eqs. 2.2-2.3);
  // the boundary layer multiplies it by the gap over the Stokes layer, a alpha / sqrt(nu / Omega) (2.6).
  double resistance = std::numbers::pi * mu * a * a * a / (4 * alpha * alpha * alpha);  // N m s
  if (law.model == AirFlow::BoundaryLayer) {
    const double Omega = rocking.norm() / alpha;
    resistance *= a * alpha * std::sqrt(Omega * law.density / mu);
  }
  // A ring's hole is open to the room (p = 0 on both edges of the annulus): the Reynolds equation over
  // b <= r <= a gives (1 - b^2/a^2)^3 of the disk's power for any conductance uniform over the face,
  // Moffatt's and the boundary layer's alike (docs/euler_disk.md 2.5a).
  if (k.holeRadius > 0) {
    const double open = 1 - (k.holeRadius * k.holeRadius) / (a * a);
    resistance *= open * open * open;
  }
  return {.torque = -resistance * rocking, .power = resistance * rocking.squaredNorm()};
}

}  // namespace coinroll::physics
