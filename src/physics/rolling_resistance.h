#pragma once
// Rolling resistance: the energy a rolling contact loses per distance travelled
// (docs/euler_disk.md §2 (c); McDonald and McDonald 2000, Leine 2009, Thorne et al. 2026).

#include "physics/contact_kinematics.h"

namespace coinroll::physics {

// N, the load at which `length` is quoted when the couple is not proportional to N.
inline constexpr double kRollingReferenceLoad = 1.0;
// rad/s, the rolling rate |psi-dot| at which `length` is quoted when the couple grows with the rate.
inline constexpr double kRollingReferenceRate = 1.0;

// rad/s. Below this rolling rate omega . h the couple fades linearly to zero instead of
// switching sign; a spin-down rolls a thousand times faster than this until it is flat. A coin whose
// rim stops rolling before it is flat (the coin toss, its last 0.77 ms) sits inside the fade, where the
// couple is viscous and stiff: rate N a / (this I_X) ~ 1e7 1/s (docs/euler_disk.md eq. 2.14a).
inline constexpr double kRollingRegularisationRate = 1e-3;

struct RollingResistance {
  double length = 2e-6;  // m, rolling-resistance length delta: the couple is delta N for a wheel
  // n: the couple is delta N_ref (N / N_ref)^n with N_ref = kRollingReferenceLoad; 1 is
  // proportional to the load, n < 1 the sublinear growth with mass measured on glass.
  double loadExponent = 1;
  // m: the couple also grows as (|psi-dot| / kRollingReferenceRate)^(m - 1), so P ~ |psi-dot|^m;
  // 1 is the wheel's constant couple, 2 the power ~ Omega^2 McDonald and McDonald (2000) measured.
  double rateExponent = 1;
  static constexpr bool kReadsNormalForce = true;
};

// P = delta N |psi-dot| (the contact moves at a |psi-dot|, resisted by (delta / a) N), done by
// the couple tau = -(delta N / cos theta) sign(omega . h) h, h = rollingAxis() (eq. 2.10), with
// delta N generalised by the load and rate exponents (eqs. 2.11, 2.11a), and its size at most N a
// (eq. 2.11d: the normal force's centre inside the coin).
Loads loads(const RollingResistance& law, const ContactKinematics& k);

}  // namespace coinroll::physics
