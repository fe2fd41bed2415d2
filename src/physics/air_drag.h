#pragma once
// Viscous drag of the air squeezed in and out of the thin gap under a nearly flat coin
// (docs/euler_disk.md §2 (a), (b)): a couple resisting the face's rocking.

#include "physics/contact_kinematics.h"

namespace coinroll::physics {

enum class AirFlow {
  Moffatt,        // lubrication flow filling the gap a alpha (Moffatt 2000, Nature 404, 833)
  BoundaryLayer,  // shear confined to the Stokes layer sqrt(nu / Omega) (Bildsten 2002, PRE 66, 056309)
};

struct AirDrag {
  AirFlow model = AirFlow::Moffatt;
  double viscosity = 1.8e-5;  // Pa s, dynamic viscosity mu of air at 20 C
  double density = 1.2;       // kg/m^3, air at 20 C and sea-level pressure (boundary-layer model only)
  static constexpr bool kReadsNormalForce = false;  // the air does not feel the load
};

// tau = -C omega_h with C = pi mu a^3 / (4 alpha^3) (Moffatt, eq. 2.2) or
// C = (pi / 4) sqrt(mu rho) a^4 |omega_h|^(1/2) alpha^(-5/2) (boundary layer, eq. 2.6); P = C |omega_h|^2.
// A ring's face is the annulus b <= r <= a: both laws times (1 - b^2 / a^2)^3 (eq. 2.5a), 0 for a hoop.
Loads loads(const AirDrag& law, const ContactKinematics& k);

}  // namespace coinroll::physics
