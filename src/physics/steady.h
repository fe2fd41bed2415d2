#pragma once
// Steady motions of the ideal rolling coin (seed section 5) for any I_X, I_Z, and the linear
// stability of each through one number K (docs/derivations.md §3): small tilt perturbations obey
// d(theta)'' = -K d(theta), so K > 0 means a bounded wobble at angular frequency sqrt(K).
// A coin with a rim (model.rim thick) uses docs/rim.md §5; a thin one computes exactly what the seed's
// formulas give. A rim with corners (edge radius < thickness / 2) has no upright steady motion: the
// contact would switch corners there, so what needs theta = 0 throws std::invalid_argument for it.

#include <optional>
#include <string_view>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/forward.h"

namespace coinroll::physics {

// Upright rolling along a straight line: theta = omega_X = omega_Y = 0, omega_Z constant. The same state
// for every coin that can roll upright; the overload with the model says whether it can (docs/rim.md
// eq. 5.4: thin or fully rounded yes, a cornered rim throws).
CoinState straightRolling(double omega_Z);
CoinState straightRolling(const CoinModel& model, double omega_Z);

// Spin below which straight rolling is unstable, rad/s (docs §3.2):
// omega_c^2 = M g a I_X / (I_Z (I_Z + M a^2)); for the disk 1/sqrt(3) in units sqrt(g/a).
// Fully rounded rim: a - rho replaces a in the gravity term, M g (a - rho) (docs/rim.md eq. 5.9).
// Throws for a cornered rim.
double criticalSpin(const CoinModel& model);

// Centre of mass at rest, the coin rolling round on its rim at tilt theta (steady state 2):
// omega_X = omega_Z = 0, omega_Y = sqrt(M g a cos(theta) / I_X) > 0. Throws std::invalid_argument
// for theta = 0 or |theta| >= pi/2.
// With a rim omega is parallel to the contact vector (A, B of docs/rim.md eq. 1.3): omega_Z = -B/A omega_Y,
// omega_Y^2 = M g A Lambda / (I_X A tan(theta) - I_Z B) (eq. 5.3); a cornered rim has no such motion
// between its balance angle and the root of the denominator, and throws there.
CoinState spinInPlace(const CoinModel& model, double theta);

// Steady circle (steady state 3) at tilt theta and spin omega_Z: omega_X = 0 and omega_Y the
// root f+ (branch = +1) or f- (branch = -1) of
//   I_X tan(theta) omega_Y^2 + (I_Z + M a^2) omega_Z omega_Y - M g a sin(theta) = 0.
// theta = 0 with branch +1 is straight rolling; branch -1 has no finite root there and throws
// std::invalid_argument, as does |theta| >= pi/2 or a branch other than +-1.
// With a rim the quadratic is P omega_Y^2 + Q omega_Z omega_Y - M g Lambda = 0 (docs/rim.md eq. 5.1).
// A cornered rim below its balance angle has circles only for |omega_Z| large enough and throws when
// none exists; at theta = 0 it throws (the contact would switch corners).
CoinState steadyCircle(const CoinModel& model, double theta, double omega_Z, int branch);

// Residual of the steady-state condition above, N m (zero on every steady state with omega_X = 0);
// with a rim the left side of docs/rim.md eq. 5.1.
double steadyResidual(const CoinModel& model, const CoinState& state);

// K, 1/s^2, of the linearised tilt dynamics about a steady state (theta0, omega_Y0, omega_Z0)
// with omega_X = 0 (docs/derivations.md eq. 3.6; with a rim docs/rim.md eq. 5.8). Straight rolling:
// K = -lambda^2 of seed 5.1. Throws for a cornered rim at theta0 = 0, where K is undefined.
double wobbleStiffness(const CoinModel& model, double theta0, double omega_Y0, double omega_Z0);

// What K says of a small tilt perturbation of a steady motion: K > 0 wobbles at sqrt(K) rad/s,
// K < 0 grows like exp(sqrt(-K) t), K = 0 is the marginal case between.
struct TiltStability {
  enum class Kind { Stable, Unstable, Marginal };
  Kind kind = Kind::Marginal;
  double rate = 0;  // rad/s: sqrt(|K|), the wobble's angular frequency or the growth rate
  double time = 0;  // s: the wobble's period 2 pi / rate, or the e-folding time 1 / rate; 0 when marginal
};
TiltStability tiltStability(double K);
// The verdict's name as the library's SteadyState and the WebAssembly core's steady report give it:
// "stable", "unstable" or "marginal".
std::string_view verdictName(TiltStability::Kind kind);

// Radii of the circles traced by the centre of mass and by the contact point in a steady motion
// with omega_X = 0, m: each point's speed over |phi-dot|. Infinite for straight rolling (phi-dot = 0).
struct CircleRadii {
  double centreOfMass = 0;  // m, R_G = a |omega_Z / phi-dot|; rim: |A omega_Z + B omega_Y| / |phi-dot|
  double contact = 0;       // m, R_C = a |psi-dot / phi-dot|; rim: A |psi-dot / phi-dot| (docs/rim.md eq. 5.10)
};
CircleRadii circleRadii(const CoinModel& model, const CoinState& steadyState);

// What `coinroll steady` prints and the library's steady() returns, computed in one place.
struct SteadyReport {
  double naturalRate = 0;                   // rad/s, sqrt(g/a)
  std::optional<double> criticalSpin;       // rad/s; absent for a rim with corners, which has no straight rolling
  double precessionRate = 0, spinRate = 0;  // rad/s, phi-dot and psi-dot
  CircleRadii radii;
  Reaction reaction;
  double stiffness = 0;  // K, 1/s^2 (wobbleStiffness)
  TiltStability stability;
};
SteadyReport steadyReport(const CoinModel& model, const CoinState& steadyState);

}  // namespace coinroll::physics
