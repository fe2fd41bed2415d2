#pragma once
// What stays fixed during a run: mass, radius, gravity, the two principal moments of an
// axisymmetric coin and the dissipation laws switched on. Kept apart from CoinState so every
// physics function reads (const CoinModel&, state) and nothing is cached behind the caller's back.

#include <optional>
#include <vector>

#include "physics/effects.h"
#include "physics/rim.h"

namespace coinroll::physics {

// Coulomb friction at the contact (docs/sliding.md).
struct Friction {
  std::optional<double> cone;  // the rolling cone's coefficient (friction_static, else friction); none: no slip monitor
  double kinetic = 0;          // the sliding contact's coefficient ("sliding": true)
};

// The rim striking the floor ("flight": true; docs/flight.md §3): Stronge's energetic restitution and
// Coulomb friction during the impulse.
struct ImpactLaw {
  double restitution = 0;  // e in [0, 1]: the normal impulse's work in restitution over its work in compression, -e^2
  double friction = 0;     // mu >= 0 during the impact
};

struct CoinModel {
  double M = 0;           // kg, mass
  double a = 0;           // m, outer radius
  double g = 0;           // m/s^2, gravitational acceleration
  double I_X = 0;         // kg m^2, moment about a diameter (I_X = I_Y by symmetry)
  double I_Z = 0;         // kg m^2, moment about the symmetry axis
  Rim rim;                // thickness 0 (the default): the seed's thin coin, bit for bit
  double holeRadius = 0;  // m, b: a ring's hole, open to the room under the face (air drag, docs/euler_disk.md 2.5a)
  std::vector<Effect> effects;  // empty: the seed's ideal rolling, energy conserved
  Friction friction{};          // the default: no cone (no slip monitor) and no sliding friction
  ImpactLaw impact{};           // the landings' law ("flight": true); the default: plastic and frictionless
};

// Thin uniform disk: I_X = M a^2 / 4, I_Z = M a^2 / 2 (seed eq. 12).
CoinModel diskModel(double M, double a, double g);

// Annulus of outer radius a and hole radius b (seed section 6):
// I_X = M (a^2 + b^2) / 4, I_Z = M (a^2 + b^2) / 2. b = a is a thin hoop.
CoinModel ringModel(double M, double a, double b, double g);

// Natural time unit sqrt(a / g), s: the seed's dimensionless time.
double naturalTime(const CoinModel& model);

// Natural angular-velocity unit sqrt(g / a), rad/s.
double naturalRate(const CoinModel& model);

}  // namespace coinroll::physics
