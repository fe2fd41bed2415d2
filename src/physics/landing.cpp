#include "physics/landing.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "physics/impact.h"
#include "physics/quaternion_dynamics.h"
#include "physics/validity.h"

namespace coinroll::physics {

namespace {

// The attitude q at upright turned to theta = side 1e-12 rad, where the rim's lowest point is that
// side's corner: at |theta| ~ 1e-16 which corner is lowest is round-off's (thetaOf and the contact
// geometry can disagree on it). The turn is about y x n, which at upright moves theta and nothing else.
// It lifts the centre by (h/2 - rho) 1e-12, M g 2.5e-15 J for a 10 g coin's 2.5 mm corner offset:
// energy the budget of a thousand landings does not see at 1e-9 (a turn of 1e-9 rad did, on a rocking
// coin's last landings; docs/flight.md eq. 4.3).
Eigen::Quaterniond pastUpright(const Eigen::Quaterniond& q, double side) {
  constexpr double kPastUpright = 1e-12;  // rad
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitY().cross(q * Eigen::Vector3d::UnitZ()).normalized();
  return (Eigen::AngleAxisd(side * kPastUpright - thetaOf(q), axis) * q).normalized();
}

// The impact of the rim's lowest point of `atTouch` at t, with the model's law (docs/flight.md §3-§5).
Landing strike(const CoinModel& model, double t, const FlightState& atTouch, double dissipated, bool plastic) {
  Landing landing{.handover = flightHandover(model, t, atTouch, dissipated)};
  const Eigen::Vector3d rim = lowestPointVector(model, atTouch.q);
  const double closing = -pointVelocity(atTouch, rim).y();
  landing.normalSpeed = std::max(closing, 0.0);
  if (std::abs(thetaOf(atTouch.q)) >= flatStopFor(model, Formulation::Quaternion).tilt) {
    landing.transition = Transition::LandsFlat;
    return landing;
  }
  // A touchdown located where the rim has just stopped closing (a graze) has nothing to absorb.
  if (closing <= 0) {
    landing.transition = Transition::BouncesEnd;
    landing.bouncesEnd = true;
    return landing;
  }
  ImpactLaw law = model.impact;
  ImpactOutcome outcome = resolveImpact(model, atTouch, law);
  // The last of a bounce sequence is made plastic, so the rim stays on the floor (docs/flight.md §4).
  const bool bouncesEnd = plastic || (!outcome.jammed && outcome.reboundSpeed < restSpeed(model));
  if (bouncesEnd && law.restitution > 0) {
    law.restitution = 0;
    outcome = resolveImpact(model, atTouch, law);
  }
  if (outcome.jammed) {
    landing.transition = Transition::Jams;
    return landing;
  }
  landing.transition = bouncesEnd ? Transition::BouncesEnd : Transition::Bounces;
  landing.handover = flightHandover(model, t, outcome.after, dissipated + outcome.energyLost);
  landing.reboundSpeed = bouncesEnd ? 0 : outcome.reboundSpeed;
  landing.energyLost = outcome.energyLost;
  landing.bouncesEnd = bouncesEnd;
  return landing;
}

}  // namespace

double restSpeed(const CoinModel& model) {
  constexpr double kRestHeight = 1e-6;  // per m of radius
  return std::sqrt(2 * model.g * kRestHeight * model.a);
}

FlightState onTheFloor(const CoinModel& model, FlightState state) {
  state.centre.y() = lowestPointDepth(model, state.q);
  return state;
}

SlidingState contactStateOf(const CoinModel& model, const FlightState& state) {
  const Eigen::Vector3d u = pointVelocity(state, lowestPointVector(model, state.q));
  return {.attitude = {.q = state.q, .omegaBody = state.omegaBody, .x = state.centre.x(), .z = state.centre.z()},
          .slip = Eigen::Vector2d(u.x(), u.z())};
}

Handover flightHandover(const CoinModel& model, double t, const FlightState& state, double dissipated) {
  return {
      .t = t, .state = contactStateOf(model, state), .forward = flightForward(model, state), .dissipated = dissipated};
}

bool belowUpright(const CoinModel& model, const FlightState& state) {
  return kineticEnergy(model, state) + model.M * model.g * state.centre.y() < uprightEnergy(model);
}

Landing touchdown(const CoinModel& model, const Handover& atTouch, bool plastic) {
  return strike(model, atTouch.t, flightStateOf(atTouch), atTouch.dissipated, plastic);
}

Landing cornerLanding(const CoinModel& model, const Handover& leaving, bool plastic) {
  // The corner the tilt moves towards lands (docs/flight.md eq. 4.3); the one the coin rolled on is
  // the band's other end.
  const FlightState before = flightStateOf(leaving);
  const double side = tiltRate(before.q, before.omegaBody) < 0 ? -1.0 : 1.0;
  FlightState atTouch = before;
  atTouch.q = pastUpright(before.q, side);
  Landing landing = strike(model, leaving.t, onTheFloor(model, atTouch), leaving.dissipated, plastic);
  if (landing.transition != Transition::BouncesEnd) return landing;
  // The rocking between the corners has died away: both ends of the flat band rest on the floor.
  const FlightState after = flightStateOf(landing.handover);
  const double still = restSpeed(model);
  const Eigen::Vector3d landed = lowestPointVector(model, after.q);
  const Eigen::Vector3d otherCorner = lowestPointVector(model, pastUpright(before.q, -side));
  if (plastic || (pointVelocity(after, landed).norm() < still && pointVelocity(after, otherCorner).norm() < still)) {
    landing.transition = Transition::BandRests;
  }
  return landing;
}

}  // namespace coinroll::physics
