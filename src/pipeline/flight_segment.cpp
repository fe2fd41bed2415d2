#include "pipeline/flight_segment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "physics/impact.h"
#include "physics/validity.h"

namespace coinroll::pipeline {

namespace {

// m, per m of radius: the rim touches when it is this far into the floor. A flight starts with the
// rim exactly on the floor (a bounce, a lift-off: onTheFloor), so the touchdown's g starts at this
// depth, above zero, however slowly the gap then grows (as t^3 after a lift-off).
constexpr double kTouchDepth = 1e-12;

// The shortest hop a flight's steps resolve, in the natural time sqrt(a / g): a rebound below the
// bounce-end's speed (eq. 4.1) lasts 2 sqrt(2e-6) ~ 3e-3 of it.
constexpr double kShortestHop = 1e-3;
// rad: the tumbling coin turns at most this per step.
constexpr double kStepTurn = std::numbers::pi / 8;

// docs/flight.md eq. (4.1): bounces end at a rebound that would lift the rim 1e-6 a.
constexpr double kRestHeight = 1e-6;

}  // namespace

integrate::Vec<kFlightSize> FlightRhs::operator()(double /*t*/, const integrate::Vec<kFlightSize>& y) const {
  integrate::Vec<kFlightSize> dy;
  dy << physics::flightRhs(model, y.head<physics::kFlightStateSize>()), 0;
  return dy;
}

physics::FlightState flightStateOf(const integrate::Vec<kFlightSize>& y) {
  return physics::toFlightState(y.head<physics::kFlightStateSize>());
}

RunSample FlightKind::sample(const integrate::Vec<kFlightSize>& y, const physics::CoinState& continuation) const {
  const physics::FlightState s = flightStateOf(y);
  const physics::QuaternionState attitude{.q = s.q, .omegaBody = s.omegaBody, .x = s.centre.x(), .z = s.centre.z()};
  return {.state = physics::toEulerState(attitude, continuation),
          .forward = physics::flightForward(model, s),
          .dissipated = y[kFlightSize - 1]};
}

integrate::Event<kFlightSize> touchdownEvent(const physics::CoinModel& model, int id) {
  return {.name = "touchdown",
          .id = id,
          .g = [model](double, const integrate::Vec<kFlightSize>& y) {
            return physics::rimGap(model, flightStateOf(y)) + kTouchDepth * model.a;
          },
          .direction = -1,
          .terminal = true};
}

physics::FlightState onTheFloor(const physics::CoinModel& model, physics::FlightState state) {
  state.centre.y() = physics::lowestPointDepth(model, state.q);
  return state;
}

integrate::SolverConfig flightSolver(const Simulation& simulation, const physics::FlightState& start) {
  const physics::CoinModel& model = simulation.model;
  const double rising =
      std::max(physics::pointVelocity(start, physics::lowestPointVector(model, start.q)).y(), 0.0);
  const double turn = start.omegaBody.norm();
  integrate::SolverConfig solver = simulation.solver;
  // No step may span a whole hop of the rim, where the gap would rise and fall back unseen: at most
  // a quarter of the rebound's flight 2 u / g, and an eighth of a turn of the tumbling coin, whose
  // rim dips towards the floor twice a turn.
  // A flight that starts in the air (a toss, a drop) crosses the floor before it can come back.
  const bool fromTheFloor = physics::rimGap(model, start) <= kTouchDepth * model.a;
  const double hop = fromTheFloor ? std::max(0.5 * rising / model.g, kShortestHop * physics::naturalTime(model))
                                  : std::numeric_limits<double>::infinity();
  solver.maxStep = std::min({solver.maxStep, hop, turn > 0 ? kStepTurn / turn : hop});
  return solver;
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
  const double restSpeed = std::sqrt(2 * model.g * kRestHeight * model.a);
  physics::ImpactOutcome outcome = physics::resolveImpact(model, atTouch, law);
  // The last of a bounce sequence is made plastic, so the rim stays on the floor (docs/flight.md §4).
  const bool bouncesEnd = plastic || (!outcome.jammed && outcome.reboundSpeed < restSpeed);
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
