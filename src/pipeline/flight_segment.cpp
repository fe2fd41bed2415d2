#include "pipeline/flight_segment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "integrate/event_location.h"
#include "physics/impact.h"
#include "physics/validity.h"

namespace coinroll::pipeline {

namespace {

// m, per m of radius: the rim touches when it is this far into the floor. A flight starts with the
// rim exactly on the floor (a bounce, a lift-off: onTheFloor), so the touchdown's g starts at this
// depth, above zero, however slowly the gap then grows (as t^3 after a lift-off).
constexpr double kTouchDepth = 1e-12;

// The shortest hop the touchdown's search resolves, in the natural time sqrt(a / g): a rebound below the
// bounce-end's speed (eq. 4.1) lasts 2 sqrt(2e-6) ~ 3e-3 of it.
constexpr double kShortestHop = 1e-3;
// rad: the tumbling coin turns at most this between two readings of its gap.
constexpr double kStepTurn = std::numbers::pi / 8;

// s: the first time the closed form's g = gap + kTouchDepth a falls through zero after t0, up to
// `until`. Before the centre comes down to reachBelowCentre no attitude can touch: the search starts
// there. From then on g is read every eighth of a turn of the coin (its rim dips towards the floor
// twice a turn) and every quarter of a rebound's hop, so no dip falls between two readings, and the
// crossing is located between the last two.
std::optional<double> touchdownAfter(const physics::CoinModel& model, double t0, const physics::FlightState& start,
                                     double until) {
  const auto g = [&](double elapsed) {
    return physics::rimGap(model, physics::flightAfter(model, start, elapsed)) + kTouchDepth * model.a;
  };
  const double high = start.centre.y() - physics::reachBelowCentre(model), up = start.velocity.y();
  double elapsed = high > 0 ? (up + std::sqrt(up * up + 2 * model.g * high)) / model.g : 0.0;
  const double rising =
      std::max(physics::pointVelocity(start, physics::lowestPointVector(model, start.q)).y(), 0.0);
  const double turn = start.omegaBody.norm();
  const bool fromTheFloor = physics::rimGap(model, start) <= kTouchDepth * model.a;
  const double hop = fromTheFloor ? std::max(0.5 * rising / model.g, kShortestHop * physics::naturalTime(model))
                                  : std::numeric_limits<double>::infinity();
  const double reading = std::min(hop, turn > 0 ? kStepTurn / turn : hop);
  // A coin dropped without spin from above falls straight: its gap, the centre's parabola less a
  // constant, falls monotonically, read every natural time.
  const double step = std::isfinite(reading) ? reading : physics::naturalTime(model);
  double before = g(elapsed);
  while (t0 + elapsed < until) {
    const double next = elapsed + step, after = g(next);
    if (before > 0 && after <= 0) return t0 + integrate::locateRoot(g, elapsed, before, next, after);
    elapsed = next, before = after;
  }
  return std::nullopt;
}

}  // namespace

FreeFlight::FreeFlight(const physics::CoinModel& model, double t0, const physics::FlightState& start,
                       double dissipated, double until)
    : model_(model), t0_(t0), start_(start), dissipated_(dissipated),
      touchdown_(touchdownAfter(model, t0, start, until)) {}

RunSample flightSample(const physics::CoinModel& model, const physics::FlightState& s, double dissipated,
                       const physics::CoinState& continuation) {
  const physics::QuaternionState attitude{.q = s.q, .omegaBody = s.omegaBody, .x = s.centre.x(), .z = s.centre.z()};
  return {.state = physics::toEulerState(attitude, continuation),
          .forward = physics::flightForward(model, s),
          .dissipated = dissipated};
}

double restSpeed(const physics::CoinModel& model) {
  constexpr double kRestHeight = 1e-6;  // per m of radius
  return std::sqrt(2 * model.g * kRestHeight * model.a);
}

physics::FlightState onTheFloor(const physics::CoinModel& model, physics::FlightState state) {
  state.centre.y() = physics::lowestPointDepth(model, state.q);
  return state;
}

Landing land(const Simulation& simulation, double t, const physics::FlightState& atTouch, double dissipated,
             bool plastic) {
  const physics::CoinModel& model = simulation.model;
  Landing landing{.state = atTouch, .dissipated = dissipated, .impact = {.t = t}};
  const Eigen::Vector3d rim = physics::lowestPointVector(model, atTouch.q);
  const double closing = -physics::pointVelocity(atTouch, rim).y();
  landing.impact.normalSpeed = std::max(closing, 0.0);
  if (std::abs(physics::thetaOf(atTouch.q)) >= physics::flatStopFor(model, physics::Formulation::Quaternion).tilt) {
    landing.next = Landing::Next::Rest;
    return landing;
  }
  // A touchdown located where the rim has just stopped closing (a graze) has nothing to absorb.
  if (closing <= 0) {
    landing.next = Landing::Next::Contact;
    landing.impact.bouncesEnd = true;
    return landing;
  }
  physics::ImpactLaw law = *simulation.flight;
  physics::ImpactOutcome outcome = physics::resolveImpact(model, atTouch, law);
  // The last of a bounce sequence is made plastic, so the rim stays on the floor (docs/flight.md §4).
  const bool bouncesEnd = plastic || (!outcome.jammed && outcome.reboundSpeed < restSpeed(model));
  if (bouncesEnd && law.restitution > 0) {
    law.restitution = 0;
    outcome = physics::resolveImpact(model, atTouch, law);
  }
  if (outcome.jammed) {
    landing.next = Landing::Next::Jam;
    return landing;
  }
  landing.next = bouncesEnd ? Landing::Next::Contact : Landing::Next::Flight;
  landing.state = outcome.after;
  landing.dissipated += outcome.energyLost;
  landing.impact.reboundSpeed = bouncesEnd ? 0 : outcome.reboundSpeed;
  landing.impact.energyLost = outcome.energyLost;
  landing.impact.bouncesEnd = bouncesEnd;
  return landing;
}

physics::SlidingState contactStateOf(const physics::CoinModel& model, const physics::FlightState& state) {
  const Eigen::Vector3d u = physics::pointVelocity(state, physics::lowestPointVector(model, state.q));
  return {.attitude = {.q = state.q, .omegaBody = state.omegaBody, .x = state.centre.x(), .z = state.centre.z()},
          .slip = Eigen::Vector2d(u.x(), u.z())};
}

physics::FlightState flightStateOf(const physics::QuaternionState& attitude, const physics::Forward& contact) {
  return {.q = attitude.q, .omegaBody = attitude.omegaBody, .centre = contact.centre, .velocity = contact.velocity};
}

}  // namespace coinroll::pipeline
