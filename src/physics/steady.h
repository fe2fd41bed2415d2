#pragma once
// Steady motions of the ideal rolling coin (seed section 5) for any I_X, I_Z, and the linear
// stability of each through one number K (docs/derivations.md §3): small tilt perturbations obey
// d(theta)'' = -K d(theta), so K > 0 means a bounded wobble at angular frequency sqrt(K).

#include "physics/coin_model.h"
#include "physics/coin_state.h"

namespace coinroll::physics {

// Upright rolling along a straight line: theta = omega_X = omega_Y = 0, omega_Z constant.
CoinState straightRolling(double omega_Z);

// Spin below which straight rolling is unstable, rad/s (docs §3.2):
// omega_c^2 = M g a I_X / (I_Z (I_Z + M a^2)); for the disk 1/sqrt(3) in units sqrt(g/a).
double criticalSpin(const CoinModel& model);

// Centre of mass at rest, the coin rolling round on its rim at tilt theta (steady state 2):
// omega_X = omega_Z = 0, omega_Y = sqrt(M g a cos(theta) / I_X) > 0. Throws std::invalid_argument
// for theta = 0 or |theta| >= pi/2.
CoinState spinInPlace(const CoinModel& model, double theta);

// Steady circle (steady state 3) at tilt theta and spin omega_Z: omega_X = 0 and omega_Y the
// root f+ (branch = +1) or f- (branch = -1) of
//   I_X tan(theta) omega_Y^2 + (I_Z + M a^2) omega_Z omega_Y - M g a sin(theta) = 0.
// theta = 0 with branch +1 is straight rolling; branch -1 has no finite root there and throws
// std::invalid_argument, as does |theta| >= pi/2 or a branch other than +-1.
CoinState steadyCircle(const CoinModel& model, double theta, double omega_Z, int branch);

// Residual of the steady-state condition above, N m (zero on every steady state with omega_X = 0).
double steadyResidual(const CoinModel& model, const CoinState& state);

// K, 1/s^2, of the linearised tilt dynamics about a steady state (theta0, omega_Y0, omega_Z0)
// with omega_X = 0 (docs/derivations.md eq. 3.6). Straight rolling: K = -lambda^2 of seed 5.1.
double wobbleStiffness(const CoinModel& model, double theta0, double omega_Y0, double omega_Z0);

// Radii of the circles traced by the centre of mass and by the contact point in a steady motion
// with omega_X = 0, m. Infinite for straight rolling (phi-dot = 0).
struct CircleRadii {
  double centreOfMass = 0;  // m, R_G = a |omega_Z / phi-dot|
  double contact = 0;       // m, R_C = a |psi-dot / phi-dot|
};
CircleRadii circleRadii(const CoinModel& model, const CoinState& steadyState);

}  // namespace coinroll::physics
