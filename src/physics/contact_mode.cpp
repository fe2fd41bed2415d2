#include "physics/contact_mode.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "physics/quaternion_dynamics.h"
#include "physics/validity.h"

namespace coinroll::physics {

namespace {

// rad: the creeping slip's direction lags its rest by at most this before it is integrated freely
// (docs/sliding.md §4.6): the lag is (turn rate of the rest) |s| / pull (eq. 4.17).
constexpr double kCreepLag = 1e-3;
// rad: a free slip is handed back to its rest only within this angle of it (docs/sliding.md §4.6).
constexpr double kCreepAlignment = 1e-5;

// Where a slide goes on once its slip has stopped: rolling when the rolling reaction at zero slip
// fits the static cone, else creeping on from zero slip, its direction at its rest (docs/sliding.md §4.5).
Mode afterSlipStops(const CoinModel& model, const QuaternionState& attitude) {
  return slideOnsetMargin(model, forward(model, attitude)) < 0 ? Mode::Creeping : Mode::Rolling;
}

// The contact's own direction while its slip has one; else any: the slip is below sliding's stop.
Eigen::Vector3d slipDirection(const SlidingState& state) {
  return state.slip.norm() > 0 ? Eigen::Vector3d(state.slip.x(), 0, state.slip.y()).normalized()
                               : Eigen::Vector3d::UnitX();
}

}  // namespace

std::string_view modeName(Mode mode) {
  switch (mode) {
    case Mode::Rolling: return "rolling";
    case Mode::Sliding: return "sliding";
    case Mode::Creeping: return "creeping";
    case Mode::Flight: return "flight";
    case Mode::Impact: return "impact";
  }
  return "?";
}

std::string_view transitionName(Transition transition) {
  switch (transition) {
    case Transition::SlideOnset: return "slide onset";
    case Transition::SlipStops: return "slip stops";
    case Transition::SlipCreeps: return "slip creeps";
    case Transition::SlipFrees: return "slip frees";
    case Transition::LiftOff: return "lift-off";
    case Transition::CornerLands: return "corner lands";
    case Transition::Touchdown: return "touchdown";
    case Transition::Bounces: return "bounces";
    case Transition::BouncesEnd: return "bounce-end";
    case Transition::BandRests: return "band rests";
    case Transition::LandsFlat: return "lands flat";
    case Transition::Jams: return "jams";
  }
  return "?";
}

FlightState flightStateOf(const QuaternionState& attitude, const Forward& forward) {
  return {.q = attitude.q, .omegaBody = attitude.omegaBody, .centre = forward.centre, .velocity = forward.velocity};
}

FlightState flightStateOf(const Handover& handover) { return flightStateOf(handover.state.attitude, handover.forward); }

Next next(const CoinModel& model, Mode mode, Transition transition, const Handover& handover) {
  const bool held = mode == Mode::Rolling || mode == Mode::Sliding || mode == Mode::Creeping;
  const bool slides = mode == Mode::Sliding || mode == Mode::Creeping;
  switch (transition) {
    // A slide that starts from rolling starts creeping from zero slip: there the slip's rest is exactly
    // the contract's direction, opposite the rolling friction force (docs/sliding.md §4.5, eq. 4.7).
    case Transition::SlideOnset:
      if (mode == Mode::Rolling) return Mode::Creeping;
      break;
    case Transition::SlipStops:
      if (slides) return afterSlipStops(model, handover.state.attitude);
      break;
    case Transition::SlipCreeps:
      if (mode == Mode::Sliding) return Mode::Creeping;
      break;
    case Transition::SlipFrees:
      if (mode == Mode::Creeping) return Mode::Sliding;
      break;
    case Transition::LiftOff:
      if (held) return Mode::Flight;
      break;
    case Transition::CornerLands:
      if (held) return Mode::Impact;
      break;
    case Transition::Touchdown:
      if (mode == Mode::Flight) return Mode::Impact;
      break;
    case Transition::Bounces:
      if (mode == Mode::Impact) return Mode::Flight;
      break;
    // The rim stays on the floor, in the mode a start there would take, unless the floor cannot hold
    // it there (N <= 0): then it flies on at once (docs/flight.md §4).
    case Transition::BouncesEnd:
      if (mode == Mode::Impact) {
        const Handover contact = heldContact(model, handover);
        if (liftOffMargin(model, contact.forward) <= 0) return Mode::Flight;
        return heldMode(model, contact.state);
      }
      break;
    // Rolling on the band is not modelled: the coin stands on its edge (docs/flight.md §4a).
    case Transition::BandRests:
      if (mode == Mode::Impact) return ModelEvent::OnEdge;
      break;
    case Transition::LandsFlat:
      if (mode == Mode::Impact) return ModelEvent::Rest;
      break;
    case Transition::Jams:
      if (mode == Mode::Impact) return ModelEvent::ImpactJam;
      break;
  }
  throw std::logic_error(std::string(modeName(mode)) + " has no transition " + std::string(transitionName(transition)));
}

Handover handedOn(const CoinModel& model, Transition transition, const Handover& handover) {
  if (transition == Transition::BouncesEnd) return heldContact(model, handover);
  if (transition != Transition::SlipStops) return handover;
  const Forward rolling = forward(model, handover.state.attitude);
  return {.t = handover.t,
          .state = {.attitude = handover.state.attitude},
          .forward = rolling,
          .dissipated = handover.dissipated + (handover.forward.energy - rolling.energy)};
}

Mode heldMode(const CoinModel& model, const SlidingState& state) {
  if (state.slip.norm() > stoppedSlip(0)) return Mode::Sliding;
  return afterSlipStops(model, state.attitude);
}

Handover heldContact(const CoinModel& model, const Handover& handover) {
  const SlidingState& state = handover.state;
  const Mode mode = heldMode(model, state);
  if (mode == Mode::Rolling) {
    return {.t = handover.t,
            .state = {.attitude = state.attitude},
            .forward = forward(model, state.attitude),
            .dissipated = handover.dissipated};
  }
  return {.t = handover.t,
          .state = mode == Mode::Sliding ? state : SlidingState{.attitude = state.attitude},
          .forward = slidingForward(model, state, model.friction.kinetic, slipDirection(state)),
          .dissipated = handover.dissipated};
}

CoinModel holdingCorner(CoinModel model, const Eigen::Quaterniond& q) {
  if (hasCorners(model)) model.rim.heldCorner = thetaOf(q) < 0 ? -1.0 : 1.0;
  return model;
}

// m/s. Sliding ends when the slip speed falls to this, not to 0, where friction's direction is no
// longer defined: the last of the slip is closed by friction at once, its kinetic energy booked as
// dissipated (docs/sliding.md §4.5). A free slip's direction turns at restoring / |s|, so the steps
// near the stop shrink with |s|; the stop must come while they are still above the integrator's
// floor of 1e-14 |t|, hence a threshold growing with t (10^-11 m/s up to 1 s: a skid switches about
// 3e-12 s early at mu g = 3 m/s^2; at 1e-12 m/s a skid at t = 4.8 s stalled).
double stoppedSlip(double t) { return 1e-11 * std::max(1.0, std::abs(t)); }

double slideOnsetMargin(const CoinModel& model, const Forward& rolling) {
  return slipMargin(model, rolling, *model.friction.cone);
}

// s. A slip closing at c m/s^2 reaches stoppedSlip(t) only stoppedSlip(t) / c before its zero: for a
// hard skid (c = 3 mu g = 5.9e4 m/s^2 at mu = 2000) 1.7e-16 s, and the steps that approach the zero's
// kink (rejected past it, docs/sliding.md §4.4) fell below the integrator's floor of 1e-14 max(1, |t|) s
// first: "integration stalled" (docs/sliding.md §4.5, "Hard skids"). Ending the slide once the slip
// would stop within ten such floors keeps the last steps above it. Only slips closing faster than
// 100 m/s^2 (10^-11 m/s over 10^-13 s) end earlier than at stoppedSlip(t): a skid with mu g above
// about 33 m/s^2 (mu > 3.4).
double slipStopLead(double t) { return 1e-13 * std::max(1.0, std::abs(t)); }

namespace {

// m/s: the slip at which a slide ends, given how fast the slip closes along its direction (m/s^2).
double stopThreshold(double t, double closingRate) { return std::max(stoppedSlip(t), slipStopLead(t) * closingRate); }

}  // namespace

double slipStopMargin(double t, const Eigen::Vector2d& slip, const Eigen::Vector2d& slipRate, double resolvedSlip) {
  const double speed = slip.norm();
  const double closing = speed > 0 ? -slip.dot(slipRate) / speed : 0.0;
  return speed - std::max(stopThreshold(t, closing), resolvedSlip);
}

double creepStopMargin(double t, const Eigen::Vector2d& slip, const Eigen::Vector2d& slipRate, double resolvedSlip,
                       const Eigen::Vector3d& rest) {
  const double closing = -(slipRate.x() * rest.x() + slipRate.y() * rest.z());
  return slip.x() * rest.x() + slip.y() * rest.z() - std::max(stopThreshold(t, closing), resolvedSlip);
}

// The rest turns with the fastest of the body's rotation, the contact's precession and the rocking
// rate sqrt(g/a) (kCreepLag).
double freeSlipSpeed(const CoinModel& model, const Forward& sliding, double pull) {
  const double turnRate =
      std::max({sliding.omega.norm(), std::abs(sliding.precessionRate), std::sqrt(model.g / model.a)});
  return kCreepLag * std::max(pull, 0.0) / turnRate;
}

// A slip that falls back to half the creep's threshold hands its direction to its rest, once it has
// come to the rest: the threshold fades to zero as the slip's angle from the rest grows to
// kCreepAlignment, so a slide that ends across the rest's pull (a skid) is integrated to its end.
//
// The rest's search costs some twenty evaluations of the slip's rate, and a slide asks at every step.
// The threshold is at most half the free slip speed at the rest's pull, and it is nonzero only within
// kCreepAlignment of the rest, where the pull differs from the slip direction's own (three
// evaluations) by a part in 1e5 unless the pull itself is next to none: a slip faster than the free
// slip speed at its own direction's pull is above the threshold whatever the rest, and its margin
// is its speed (positive as the true margin is, so the event sees the same crossings).
double slipCreepMargin(const CoinModel& model, const SlidingStateVec& y, const Forward& sliding) {
  const SlidingState state = toSlidingState(y);
  const Eigen::Vector2d& slip = state.slip;
  const double pullHere = slipDirectionPull(model, state, model.friction.kinetic);
  if (slip.norm() > freeSlipSpeed(model, sliding, pullHere)) return slip.norm();
  const std::optional<Creep> creep = findCreep(model, y, model.friction.kinetic);
  if (!creep) return slip.norm();
  const Eigen::Vector2d rest(creep->slipHat.x(), creep->slipHat.z());
  const double angleFromRest = std::acos(std::clamp(rest.dot(slip.normalized()), -1.0, 1.0));
  const double nearness = std::max(0.0, 1 - angleFromRest / kCreepAlignment);
  return slip.norm() - 0.5 * nearness * freeSlipSpeed(model, sliding, creep->pull);
}

double slipFreeMargin(const CoinModel& model, const SlidingStateVec& y, const Forward& sliding) {
  const double pull = findCreep(model, y, model.friction.kinetic).value_or(Creep{}).pull;
  return toSlidingState(y).slip.norm() - freeSlipSpeed(model, sliding, pull);
}

}  // namespace coinroll::physics
