#include "pipeline/hybrid_run.h"

#include <memory>
#include <utility>
#include <variant>

#include "physics/landing.h"
#include "physics/sliding_rhs.h"
#include "pipeline/contact_segment.h"
#include "pipeline/flight_segment.h"
#include "pipeline/formulation_run.h"
#include "pipeline/trajectory_motion.h"
#include "pipeline/validity_events.h"

namespace coinroll::pipeline {

namespace {

using physics::Formulation;
using physics::Mode;
using physics::ModelEvent;
using physics::Transition;

constexpr int kRollingSize = physics::kQuaternionStateSize + 1;  // with the dissipated energy
constexpr int kSlidingSize = physics::kSlidingBudgetSize;

// Stick-slip: more switches than this within one simulated second end the run (docs/sliding.md §4).
constexpr std::size_t kMaxSwitchesPerSecond = 1000;
// A rim chattering on the floor: the impact past this many within one simulated second ends the
// bounces (docs/flight.md §4).
constexpr std::size_t kMaxImpactsPerSecond = 1000;

physics::SlidingState slidingStateOf(const integrate::Vec<kSlidingSize>& y) {
  return physics::toSlidingState(y.head<physics::kSlidingStateSize>());
}

physics::QuaternionState rollingStateOf(const integrate::Vec<kRollingSize>& y) {
  return physics::toQuaternionState(y.head<physics::kQuaternionStateSize>());
}

// A sliding state with the dissipated energy last, read in the seed's variables (TrajectoryMotion's Kind).
struct SlidingKind {
  using Rhs = physics::SlidingRhs;
  static constexpr bool kContinuesAngles = true;

  physics::SlidingRhs sliding;

  const physics::SlidingRhs& rhs() const { return sliding; }
  RunSample sample(const integrate::Vec<kSlidingSize>& y, const physics::CoinState& continuation) const {
    return {.state = physics::toEulerState(slidingStateOf(y).attitude, continuation),
            .forward = sliding.forward(y.head<physics::kSlidingStateSize>()),
            .dissipated = y[kSlidingSize - 1]};
  }
};

// The transition an event hit stands for; none for a model event's.
template <int N>
std::optional<Transition> transitionOf(const std::optional<integrate::EventHit<N>>& hit) {
  if (!hit || hit->id < kFirstSwitchId) return std::nullopt;
  return static_cast<Transition>(hit->id - kFirstSwitchId);
}

using RollingKind = FormulationKind<Formulation::Quaternion, kRollingSize>;

class RollingSegment final : public TrajectoryMotion<kRollingSize, RollingKind, ContactSegment> {
 public:
  using TrajectoryMotion::TrajectoryMotion;

  std::optional<SegmentEnd> end() const override {
    const std::optional<Transition> transition = transitionOf(endHit());
    if (!transition) return std::nullopt;
    const physics::QuaternionState state = rollingStateOf(endHit()->y);
    return SegmentEnd{.transition = *transition,
                      .handover = {.t = endHit()->t,
                                   .state = {.attitude = state},
                                   .forward = physics::forward(kind().model, state),
                                   .dissipated = endHit()->y[kRollingSize - 1]}};
  }
};

class SlidingSegment final : public TrajectoryMotion<kSlidingSize, SlidingKind, ContactSegment> {
 public:
  using TrajectoryMotion::TrajectoryMotion;

  std::optional<SegmentEnd> end() const override {
    const std::optional<Transition> transition = transitionOf(endHit());
    if (!transition) return std::nullopt;
    const double t = endHit()->t;
    const integrate::Vec<kSlidingSize> y =
        *transition == Transition::SlipStops ? kind().sliding.closedSlip(t, endHit()->y) : endHit()->y;
    return SegmentEnd{.transition = *transition,
                      .handover = {.t = t,
                                   .state = slidingStateOf(y),
                                   .forward = kind().sliding.forward(y.head<physics::kSlidingStateSize>()),
                                   .dissipated = y[kSlidingSize - 1]}};
  }
};

// The events of a held contact's geometry (the flat stop, the corner at upright) and its lift-off.
// With flight the coin leaves the floor where N falls through zero, read inside each step as the cone
// is (a hop shorter than a step shows no sign change), and lands its other corner at upright. Without,
// both end the run: N < 0 is never integrated as a contact, whatever on_invalid says, since the
// sliding law's friction -mu N s_hat would then push the coin along its slip and make energy (+46 %
// in one scene; docs/sliding.md §4.5); on_invalid "warn" goes on past the rolling-only model's slip,
// which the sliding model replaces.
template <int N>
std::vector<integrate::Event<N>> heldContactEvents(const physics::CoinModel& model, bool flight,
                                                   std::function<double(const integrate::Vec<N>&)> theta,
                                                   std::function<double(const integrate::Vec<N>&)> tiltRate,
                                                   std::function<physics::Forward(const integrate::Vec<N>&)> forward) {
  using Y = integrate::Vec<N>;
  std::vector<integrate::Event<N>> events =
      geometryEvents<N>(model, Formulation::Quaternion, std::move(theta), std::move(tiltRate), flight);
  const auto liftOff = [model, forward](double, const Y& y) { return physics::liftOffMargin(model, forward(y)); };
  if (!flight) {
    events.push_back(modelEvent<N>(ModelEvent::LiftOff, liftOff, -1, true));
    return events;
  }
  integrate::Event<N> lifts = transitionEvent<N>(Transition::LiftOff, liftOff);
  lifts.interiorChecks = kConeGrazeChecks;
  events.push_back(std::move(lifts));
  return events;
}

// decided (stop_when_decided, docs/flight.md §5a): the energy falls below standing upright's.
// `energy` reads an integrated state's.
template <int N>
integrate::Event<N> decidedEvent(const physics::CoinModel& model,
                                 std::function<double(const integrate::Vec<N>&)> energy) {
  return modelEvent<N>(
      ModelEvent::Decided,
      [energy, upright = physics::uprightEnergy(model)](double, const integrate::Vec<N>& y) {
        return energy(y) - upright;
      },
      -1, true);
}

bool slides(Mode mode) { return mode == Mode::Sliding || mode == Mode::Creeping; }

}  // namespace

HybridRun::HybridRun(const Simulation& simulation)
    : simulation_(simulation), pace_(0, simulation.solver.endTime, simulation.solver.maxSteps) {
  const physics::CoinModel& model = simulation_.model;
  const physics::QuaternionState start = physics::fromEulerState(simulation.initial);
  const physics::Forward rolling = physics::forward(model, start);
  const std::optional<physics::FlightState> flying = flightStart(simulation);
  // A coin that starts with too little energy to pass upright has its face decided before it moves.
  if (const physics::FlightState at = flying.value_or(physics::flightStateOf(start, rolling));
      simulation.stopWhenDecided && physics::belowUpright(model, at)) {
    ending_ = Ending{.event = ModelEvent::Decided, .t = 0, .state = at, .dissipated = 0};
  }
  if (flying) {
    startFlight(0, *flying, 0);
    return;
  }
  const Eigen::Vector2d velocity =
      simulation.initialVelocity.value_or(Eigen::Vector2d(rolling.velocity.x(), rolling.velocity.z()));
  const physics::Handover held = physics::heldContact(
      model, {.state = {.attitude = start, .slip = physics::slipOf(model, start, velocity)}, .forward = rolling});
  const Mode mode = physics::heldMode(model, held.state);
  // A start off the rolling constraint is stated as a landing's is (docs/contract.md §6).
  noteSwitch(Mode::Impact, mode, 0);
  if (mode == Mode::Rolling) {
    startRolling(held);
  } else {
    startSliding(held, mode);
  }
}

HybridRun::~HybridRun() = default;

void HybridRun::startRolling(const physics::Handover& start) {
  using Y = integrate::Vec<kRollingSize>;
  mode_ = Mode::Rolling;
  const physics::CoinModel model = physics::holdingCorner(simulation_.model, start.state.attitude.q);
  const auto forward =
      remembering<kRollingSize>([model](const Y& y) { return physics::forward(model, rollingStateOf(y)); });
  std::vector<integrate::Event<kRollingSize>> events = heldContactEvents<kRollingSize>(
      model, simulation_.flight, [](const Y& y) { return thetaOf<Formulation::Quaternion, kRollingSize>(y); },
      [](const Y& y) { return tiltRateOf<Formulation::Quaternion, kRollingSize>(y); }, forward);
  integrate::Event<kRollingSize> slides = transitionEvent<kRollingSize>(
      Transition::SlideOnset,
      [model, forward](double, const Y& y) { return physics::slideOnsetMargin(model, forward(y)); });
  slides.interiorChecks = kConeGrazeChecks;
  events.push_back(std::move(slides));
  if (simulation_.stopWhenDecided) {
    events.push_back(decidedEvent<kRollingSize>(model, [forward](const Y& y) { return forward(y).energy; }));
  }
  Y y0;
  y0 << physics::toVector(start.state.attitude), start.dissipated;
  segment_ = std::make_unique<RollingSegment>(RollingKind{model}, start.t, y0, simulation_.solver, std::move(events),
                                              simulation_.duration);
}

void HybridRun::startSliding(const physics::Handover& start, Mode mode) {
  using Y = integrate::Vec<kSlidingSize>;
  mode_ = mode;
  const physics::SlidingState& state = start.state;
  const physics::CoinModel model = physics::holdingCorner(simulation_.model, state.attitude.q);
  const Eigen::Vector2d along = state.slip.norm() > 0 ? state.slip.normalized() : Eigen::Vector2d::UnitX();
  const physics::SlidingRhs rhs{.model = model, .mode = mode, .direction = Eigen::Vector3d(along.x(), 0, along.y())};
  const auto forwardOf =
      remembering<kSlidingSize>([rhs](const Y& y) { return rhs.forward(y.head<physics::kSlidingStateSize>()); });
  std::vector<integrate::Event<kSlidingSize>> events = heldContactEvents<kSlidingSize>(
      model, simulation_.flight, [](const Y& y) { return physics::thetaOf(slidingStateOf(y).attitude.q); },
      [](const Y& y) {
        const physics::QuaternionState attitude = slidingStateOf(y).attitude;
        return physics::tiltRate(attitude.q, attitude.omegaBody);
      },
      forwardOf);
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::Painleve,
      [forwardOf](double, const Y& y) { return forwardOf(y).normalEffectiveMass - physics::kPainleveMargin; }, -1,
      true));
  const double resolvedSlip = physics::kResolvedSlipPerAtol * simulation_.solver.atol;
  if (mode == Mode::Sliding) {
    events.push_back(transitionEvent<kSlidingSize>(Transition::SlipStops, [rhs, resolvedSlip](double at, const Y& y) {
      return physics::slipStopMargin(at, slidingStateOf(y).slip, rhs.slipRate(at, y), resolvedSlip);
    }));
    events.push_back(transitionEvent<kSlidingSize>(Transition::SlipCreeps, [model, forwardOf](double, const Y& y) {
      return physics::slipCreepMargin(model, y.head<physics::kSlidingStateSize>(), forwardOf(y));
    }));
  } else {
    // Friction keeps to the rest while the slip passes zero, so the slip crosses it smoothly and its
    // length has a kink there that a step can jump: the stop is found on the slip along the rest.
    events.push_back(transitionEvent<kSlidingSize>(Transition::SlipStops, [rhs, resolvedSlip](double at, const Y& y) {
      const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
      return physics::creepStopMargin(at, physics::toSlidingState(coin).slip, rhs.slipRate(at, y), resolvedSlip,
                                      rhs.frictionDirection(coin));
    }));
    events.push_back(transitionEvent<kSlidingSize>(
        Transition::SlipFrees,
        [rhs](double, const Y& y) {
          const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
          return physics::slipFreeMargin(rhs.model, coin, rhs.forward(coin));
        },
        +1));
  }
  if (simulation_.stopWhenDecided) {
    events.push_back(decidedEvent<kSlidingSize>(model, [forwardOf](const Y& y) { return forwardOf(y).energy; }));
  }
  Y y0;
  y0 << physics::toVector(state), start.dissipated;
  segment_ = std::make_unique<SlidingSegment>(SlidingKind{rhs}, start.t, y0, simulation_.solver, std::move(events),
                                              simulation_.duration);
}

void HybridRun::startFlight(double t, const physics::FlightState& state, double dissipated) {
  mode_ = Mode::Flight;
  segment_ = std::make_unique<FlightSegment>(simulation_.model, t, state, dissipated, simulation_.duration);
}

bool HybridRun::enter(Mode from, Transition transition, const physics::Handover& handover) {
  const physics::CoinModel& model = simulation_.model;
  const physics::Next next = physics::next(model, from, transition, handover);
  if (const auto* event = std::get_if<ModelEvent>(&next)) {
    endAt(*event, handover);
    return false;
  }
  const Mode mode = std::get<Mode>(next);
  const physics::Handover start = physics::handedOn(model, transition, handover);
  noteSwitch(from, mode, start.t);
  switch (mode) {
    case Mode::Rolling: startRolling(start); return true;
    case Mode::Sliding:
    case Mode::Creeping: startSliding(start, mode); return true;
    case Mode::Flight:
      startFlight(start.t, physics::onTheFloor(model, physics::flightStateOf(start)), start.dissipated);
      return true;
    case Mode::Impact: return strike(from, start);
  }
  return false;
}

bool HybridRun::strike(Mode from, const physics::Handover& handover) {
  const physics::CoinModel& model = simulation_.model;
  std::size_t recent = 0;
  for (const ImpactRecord& impact : impacts_) recent += impact.t > handover.t - 1 ? 1 : 0;
  const bool chattering = recent >= kMaxImpactsPerSecond;
  const bool corner = from != Mode::Flight;
  const physics::Landing landing =
      corner ? physics::cornerLanding(model, handover, chattering) : physics::touchdown(model, handover, chattering);
  impacts_.push_back({.t = handover.t,
                      .normalSpeed = landing.normalSpeed,
                      .reboundSpeed = landing.reboundSpeed,
                      .energyLost = landing.energyLost,
                      .bouncesEnd = landing.bouncesEnd,
                      .corner = corner});
  // An impact takes energy at once, so the fall below standing upright's is read here, not located.
  const physics::Handover& after = landing.handover;
  const bool goesOn = landing.transition == Transition::Bounces || landing.transition == Transition::BouncesEnd;
  if (goesOn && simulation_.stopWhenDecided && physics::belowUpright(model, physics::flightStateOf(after))) {
    endAt(ModelEvent::Decided, after);
    return false;
  }
  return enter(Mode::Impact, landing.transition, after);
}

void HybridRun::endAt(ModelEvent event, const physics::Handover& handover) {
  ending_ = Ending{
      .event = event, .t = handover.t, .state = physics::flightStateOf(handover), .dissipated = handover.dissipated};
}

void HybridRun::noteSwitch(Mode from, Mode to, double t) {
  if (slides(to) && !slides(from)) switches_.push_back({t, true});
  if (to == Mode::Rolling && slides(from)) switches_.push_back({t, false});
}

// Past the limit the run ends: stick-slip, unless corner landings at upright come between the
// switches. Then the switching is the flat band rocking on the floor as its landings accumulate
// (docs/flight.md §4a; each landing leaves the rim sliding, then rolling), and its end is the band's,
// on-edge. Stick-slip without the band has no corner landings at all; the band's rocking makes at most
// two switches per landing.
bool HybridRun::tooManySwitches(const physics::Handover& handover) {
  const double t = handover.t;
  std::size_t recent = 0, cornerLandings = 0;
  for (const ModeSwitch& w : switches_) recent += w.t > t - 1 ? 1 : 0;
  if (recent < kMaxSwitchesPerSecond) return false;
  for (const ImpactRecord& impact : impacts_) cornerLandings += impact.corner && impact.t > t - 1 ? 1 : 0;
  if (3 * cornerLandings >= recent) {
    endAt(ModelEvent::OnEdge, handover);
  } else {
    switchRefused_ = true;
  }
  return true;
}

bool HybridRun::switchIfDue() {
  const std::optional<SegmentEnd> end = segment_->end();
  if (!end) return false;
  // The rolling-sliding switches count towards stick-slip's bound; the slide's own hand-overs between
  // free and creeping, and the flight's, do not.
  const bool countsToStickSlip = end->transition == Transition::SlideOnset || end->transition == Transition::SlipStops;
  if (countsToStickSlip && tooManySwitches(end->handover)) return false;
  // The finished segment's crossings gone past and its work, kept before it is replaced; the run's
  // pace is judged on all its segments' steps.
  const std::vector<RunEvent> crossings = segment_->warnings();
  warnings_.insert(warnings_.end(), crossings.begin(), crossings.end());
  finishedStats_ += segment_->stats();
  pace_.afterSteps(finishedStats_.acceptedSteps, end->handover.t);
  return enter(mode_, end->transition, end->handover);
}

std::optional<RunSample> HybridRun::sampleAt(double t, const physics::CoinState& continuation) {
  if (ending_ && t > ending_->t) return std::nullopt;
  for (;;) {
    if (std::optional<RunSample> sample = segment_->sampleAt(t, continuation)) {
      sample->impacts = static_cast<int>(impacts_.size());
      return sample;
    }
    if (!switchIfDue()) return std::nullopt;
  }
}

std::optional<RunEvent> HybridRun::stoppedBy(const physics::CoinState& continuation) const {
  if (ending_) {
    if (ending_->t > simulation_.duration) return std::nullopt;
    return runEventOf(static_cast<int>(ending_->event), ending_->t,
                      flightSample(simulation_.model, ending_->state, ending_->dissipated, continuation));
  }
  // A switch found before the duration but after the last query has not stopped the run: asked now,
  // the run would have named it stick-slip (a sweep whose duration fell between a bounce's touchdown
  // and the next summary point ended `stick-slip`).
  if (segment_->end() && !switchRefused_) return std::nullopt;
  return segment_->stoppedBy(continuation);
}

std::vector<RunEvent> HybridRun::warnings() const {
  std::vector<RunEvent> all = warnings_;
  const std::vector<RunEvent> current = segment_->warnings();
  all.insert(all.end(), current.begin(), current.end());
  return all;
}

integrate::Stats HybridRun::stats() const {
  integrate::Stats total = finishedStats_;
  total += segment_->stats();
  return total;
}

}  // namespace coinroll::pipeline
