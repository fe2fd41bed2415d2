#pragma once
// Pivoting (drilling) friction: a couple about the floor normal from the finite contact patch
// (docs/euler_disk.md §2 (d)).

#include "physics/contact_kinematics.h"

namespace coinroll::physics {

// rad/s. Below this pivoting rate the couple fades linearly to zero instead of switching sign.
inline constexpr double kPivotRegularisationRate = 1e-3;

struct SpinFriction {
  // m, l: the couple is l N. Coulomb friction mu_s over a uniformly loaded circular patch of
  // radius r_p gives l = (2/3) mu_s r_p (eq. 2.13).
  double length = 5e-6;
  static constexpr bool kReadsNormalForce = true;
};

// tau = -l N sign(omega_n) e_y, omega_n = omega . e_y; P = l N |omega_n| (eq. 2.12).
Loads loads(const SpinFriction& law, const ContactKinematics& k);

}  // namespace coinroll::physics
