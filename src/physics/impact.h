#pragma once
// The rim striking the floor (docs/flight.md §3): an instantaneous impulse at the rim's lowest point
// with Stronge's energetic coefficient of restitution and Coulomb friction, which never creates
// energy, whatever the slip does during the impact.

#include <Eigen/Core>

#include "physics/coin_model.h"
#include "physics/flight.h"

namespace coinroll::physics {

struct ImpactOutcome {
  FlightState after;                                  // velocities changed, attitude and centre as before
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();  // P, N s, floor components, at the contact
  double approachSpeed = 0;  // m/s, -u_n before: how fast the contact point closed on the floor
  double reboundSpeed = 0;   // m/s, u_n after (>= 0)
  double energyLost = 0;     // J, -Delta T of eq. (3.3), >= 0
  Eigen::Vector3d slipAfter = Eigen::Vector3d::Zero();  // m/s, the contact point's horizontal velocity after
  bool jammed = false;  // du_n/dp <= 0 while slipping: no impact of this kind (docs/flight.md §3, jam)
};

// K, m/(kg): the contact point's velocity change per unit impulse there, eq. (3.2).
Eigen::Matrix3d contactCompliance(const CoinModel& model, const Eigen::Quaterniond& unitQ, const Eigen::Vector3d& r);

// The impact of `state` at its rim's lowest point. Precondition: that point approaches the floor
// (u . e_y < 0).
ImpactOutcome resolveImpact(const CoinModel& model, const FlightState& state, const ImpactLaw& law);

}  // namespace coinroll::physics
