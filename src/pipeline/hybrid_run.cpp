#include "pipeline/hybrid_run.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <utility>

#include "physics/contact_mode.h"
#include "pipeline/flight_segment.h"
#include "pipeline/formulation_run.h"
#include "pipeline/trajectory_motion.h"
#include "pipeline/validity_events.h"

namespace coinroll::pipeline {

namespace {

using physics::Formulation;
using physics::ModelEvent;

constexpr int kRollingSize = physics::kQuaternionStateSize + 1;  // with the dissipated energy
constexpr int kSlidingSize = physics::kSlidingStateSize + 1;

// The switches' event ids, past ModelEvent's values; where each is crossed is physics/contact_mode.h's rule.
constexpr int kSlideOnset = kFirstSwitchId;      // rolling: the reaction reaches the cone
constexpr int kSlipStops = kFirstSwitchId + 1;   // sliding: the slip speed falls to stoppedSlip(t)
constexpr int kSlipFrees = kFirstSwitchId + 2;   // creeping: the slip's direction is slow enough to integrate
constexpr int kSlipCreeps = kFirstSwitchId + 3;  // sliding: the slip's direction is too fast to integrate
constexpr int kLiftsOff = kFirstSwitchId + 4;    // rolling or sliding with flight: N falls through zero
constexpr int kTouchdown = kFirstSwitchId + 5;   // flight: the rim reaches the floor
constexpr int kCornerLands = kFirstSwitchId + 6;  // rolling or sliding with flight: a cornered rim passes upright

// A slide's slip stops at no less than this many times solver.atol (docs/sliding.md eq. 4.18): the
// integrator holds the slip's components to about atol, and a slip a few atol long chatters about
// zero, its direction flipping inside each step, on steps of its own |s| / (restoring rate). One
// landing's slide at the default atol of 1e-12 sat at 1.4e-11 m/s (14 atol) on steps of 8e-11 s,
// 2.2 million of them, and stopped at 20 atol or more; 100 leaves a factor of 7.
constexpr double kResolvedSlipPerAtol = 100;

// Stick-slip: more switches than this within one simulated second end the run (docs/sliding.md §4).
constexpr std::size_t kMaxSwitchesPerSecond = 1000;
// A rim chattering on the floor: the impact past this many within one simulated second ends the
// bounces (docs/flight.md §4).
constexpr std::size_t kMaxImpactsPerSecond = 1000;

// The sliding segment's right-hand side, with Coulomb friction model.friction.kinetic.
struct SlidingRhs {
  physics::CoinModel model;
  // Sliding or Creeping.
  physics::ContactMode mode = physics::ContactMode::Sliding;
  Eigen::Vector3d direction;  // free: s_hat while the slip is below round-off

  // The last state's creeping friction direction, shared by the segment's copies of this
  // right-hand side: a step's last stage and the events at its end ask for the same state, and the
  // rest's search costs some twenty evaluations. A pure function's memo: the bits do not change.
  struct Remembered {
    physics::SlidingStateVec y;
    Eigen::Vector3d direction;
  };
  std::shared_ptr<std::optional<Remembered>> lastDirection = std::make_shared<std::optional<Remembered>>();

  // Creeping: along the rest, searched from the segment's direction where rolling leaves every
  // direction neutral (a trial state past zero slip must not flip friction with it, or the slip's
  // stop is never crossed); where a trial state has no rest, along the slip itself, as when free.
  Eigen::Vector3d frictionDirection(const physics::SlidingStateVec& y) const {
    std::optional<Remembered>& last = *lastDirection;
    if (last && std::memcmp(last->y.data(), y.data(), sizeof(double) * y.size()) == 0) return last->direction;
    last = Remembered{.y = y, .direction = searchFrictionDirection(y)};
    return last->direction;
  }
  Eigen::Vector3d searchFrictionDirection(const physics::SlidingStateVec& y) const {
    if (const std::optional<physics::Creep> creep = physics::findCreep(model, y, model.friction.kinetic, direction)) {
      return creep->slipHat;
    }
    const Eigen::Vector2d slip = y.tail<2>();
    return slip.norm() > physics::kSlipRoundOff ? Eigen::Vector3d(slip.x() / slip.norm(), 0, slip.y() / slip.norm())
                                                : direction;
  }
  physics::Forward forward(const physics::SlidingStateVec& y) const {
    const physics::SlidingState state = physics::toSlidingState(y);
    const double mu = model.friction.kinetic;
    return mode == physics::ContactMode::Sliding ? physics::slidingForward(model, state, mu, direction)
                                                 : physics::slidingForwardAlong(model, state, mu, frictionDirection(y));
  }
  integrate::Vec<kSlidingSize> operator()(double /*t*/, const integrate::Vec<kSlidingSize>& y) const {
    const physics::SlidingStateVec& coin = y.head<physics::kSlidingStateSize>();
    const double mu = model.friction.kinetic;
    const physics::SlidingRates r = mode == physics::ContactMode::Sliding
                                        ? physics::slidingRates(model, coin, mu, direction)
                                        : physics::slidingRatesAlong(model, coin, mu, frictionDirection(coin));
    integrate::Vec<kSlidingSize> dy;
    dy << r.dy, r.power;
    return dy;
  }
};

physics::SlidingState slidingStateOf(const integrate::Vec<kSlidingSize>& y) {
  return physics::toSlidingState(y.head<physics::kSlidingStateSize>());
}

// m/s^2: the slip's rate, for the stop's rule (physics::slipStopMargin).
Eigen::Vector2d slipRateOf(const SlidingRhs& rhs, double t, const integrate::Vec<kSlidingSize>& y) {
  return rhs(t, y).segment<2>(physics::kSlidingStateSize - 2);
}

physics::QuaternionState rollingStateOf(const integrate::Vec<kRollingSize>& y) {
  return physics::toQuaternionState(y.head<physics::kQuaternionStateSize>());
}

// A sliding state with the dissipated energy last, read in the seed's variables (TrajectoryMotion's Kind).
struct SlidingKind {
  using Rhs = SlidingRhs;
  static constexpr bool kContinuesAngles = true;

  SlidingRhs sliding;

  const SlidingRhs& rhs() const { return sliding; }
  RunSample sample(const integrate::Vec<kSlidingSize>& y, const physics::CoinState& continuation) const {
    return {.state = physics::toEulerState(slidingStateOf(y).attitude, continuation),
            .forward = sliding.forward(y.head<physics::kSlidingStateSize>()),
            .dissipated = y[kSlidingSize - 1]};
  }
};

// The attitude q at upright turned to theta = side 1e-12 rad, where the rim's lowest point is that
// side's corner: at |theta| ~ 1e-16 which corner is lowest is round-off's (thetaOf and the contact
// geometry can disagree on it). The turn is about y x n, which at upright moves theta and nothing else.
// It lifts the centre by (h/2 - rho) 1e-12, M g 2.5e-15 J for a 10 g coin's 2.5 mm corner offset:
// energy the budget of a thousand landings does not see at 1e-9 (a turn of 1e-9 rad did, on a rocking
// coin's last landings).
Eigen::Quaterniond pastUpright(const Eigen::Quaterniond& q, double side) {
  constexpr double kPastUpright = 1e-12;  // rad
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitY().cross(q * Eigen::Vector3d::UnitZ()).normalized();
  return (Eigen::AngleAxisd(side * kPastUpright - physics::thetaOf(q), axis) * q).normalized();
}

// `model` holding the corner a contact segment starting at attitude q rolls or slides on (Rim::heldCorner):
// its equations then continue smoothly past upright and the corner-switch event is located on them.
physics::CoinModel holdingCorner(physics::CoinModel model, const Eigen::Quaterniond& q) {
  if (physics::hasCorners(model)) model.rim.heldCorner = physics::thetaOf(q) < 0 ? -1.0 : 1.0;
  return model;
}

template <int N>
integrate::Event<N> switchEvent(int id, const char* name, std::function<double(double, const integrate::Vec<N>&)> g,
                                int direction = -1) {
  return {.name = name, .id = id, .g = std::move(g), .direction = direction, .terminal = true};
}

}  // namespace

// What a segment that ended in a switch hands to the next one.
struct Handover {
  int id = 0;                   // the switch: kSlideOnset, kSlipStops, kSlipFrees or kSlipCreeps
  double t = 0;                 // s
  physics::SlidingState state;  // rolling hands on zero slip
  physics::FlightState flight;  // kLiftsOff, kTouchdown: the free coin's state
  physics::Forward forward;     // the ending segment's forward pass at the switch
  double dissipated = 0;        // J
};

class ContactSegment : public Motion {
 public:
  // The switch that ended this segment; none while it runs or when a model event ended it.
  virtual std::optional<Handover> handover() const = 0;
};

namespace {

using RollingKind = FormulationKind<Formulation::Quaternion, kRollingSize>;

class RollingSegment final : public TrajectoryMotion<kRollingSize, RollingKind, ContactSegment> {
 public:
  using TrajectoryMotion::TrajectoryMotion;

  std::optional<Handover> handover() const override {
    const auto& hit = endHit();
    if (!hit || (hit->id != kSlideOnset && hit->id != kLiftsOff && hit->id != kCornerLands)) return std::nullopt;
    const physics::QuaternionState state = rollingStateOf(hit->y);
    const physics::Forward forward = physics::forward(kind().model, state);
    return Handover{.id = hit->id,
                    .t = hit->t,
                    .state = {.attitude = state},
                    .flight = flightStateOf(state, forward),
                    .forward = forward,
                    .dissipated = hit->y[kRollingSize - 1]};
  }
};

class SlidingSegment final : public TrajectoryMotion<kSlidingSize, SlidingKind, ContactSegment> {
 public:
  using TrajectoryMotion::TrajectoryMotion;

  std::optional<Handover> handover() const override {
    const auto& hit = endHit();
    if (!hit || (hit->id != kSlipStops && hit->id != kSlipCreeps && hit->id != kSlipFrees && hit->id != kLiftsOff &&
                 hit->id != kCornerLands)) {
      return std::nullopt;
    }
    const integrate::Vec<kSlidingSize> y = hit->id == kSlipStops ? closedSlip(hit->t, hit->y) : hit->y;
    const physics::SlidingState state = slidingStateOf(y);
    const physics::Forward forward = kind().sliding.forward(y.head<physics::kSlidingStateSize>());
    return Handover{.id = hit->id,
                    .t = hit->t,
                    .state = state,
                    .flight = flightStateOf(state.attitude, forward),
                    .forward = forward,
                    .dissipated = y[kSlidingSize - 1]};
  }

 private:
  // A slide ended by physics::slipStopLead (a slip closing faster than 100 m/s^2) stops with up to
  // 1e-13 s of slip left, whose centre velocity the roll would drop at once: M v |s| of energy, 2.4e-7 of
  // a hard skid's work. That last |s| / (closing rate) of sliding is applied as one increment instead
  // (docs/sliding.md §4.4), so the roll starts from the skid's closed form to O(lead^2); a slide that
  // reached physics::stoppedSlip(t) is handed over as before.
  integrate::Vec<kSlidingSize> closedSlip(double t, const integrate::Vec<kSlidingSize>& y) const {
    const integrate::Vec<kSlidingSize> rate = kind().sliding(t, y);
    const Eigen::Vector2d slip = slidingStateOf(y).slip;
    const double speed = slip.norm();
    const double closing = speed > 0 ? -slip.dot(rate.segment<2>(physics::kSlidingStateSize - 2)) / speed : 0.0;
    if (!(physics::slipStopLead(t) * closing > physics::stoppedSlip(t))) return y;
    return y + (speed / closing) * rate;
  }
};

class FlightSegment final : public ContactSegment {
 public:
  FlightSegment(const physics::CoinModel& model, double t0, const physics::FlightState& start, double dissipated,
                double duration)
      : flight_(model, t0, start, dissipated, duration), duration_(duration) {}

  bool continuesAngles() const override { return true; }

  std::optional<RunSample> sampleAt(double t, const physics::CoinState& continuation) override {
    if (flight_.touchdown() && t > *flight_.touchdown()) return std::nullopt;
    return flight_.sample(flight_.at(t), continuation);
  }

  std::optional<RunEvent> stoppedBy(const physics::CoinState& continuation) const override {
    if (!flight_.touchdown() || *flight_.touchdown() > duration_) return std::nullopt;
    const double t = *flight_.touchdown();
    return runEventOf(kTouchdown, t, flight_.sample(flight_.at(t), continuation));
  }

  std::vector<RunEvent> warnings() const override { return {}; }
  integrate::Stats stats() const override { return {}; }

  std::optional<Handover> handover() const override {
    if (!flight_.touchdown()) return std::nullopt;
    const double t = *flight_.touchdown();
    const physics::FlightState state = flight_.at(t);
    return Handover{.id = kTouchdown,
                    .t = t,
                    .state = contactStateOf(flight_.model(), state),
                    .flight = state,
                    .forward = physics::flightForward(flight_.model(), state),
                    .dissipated = flight_.dissipated()};
  }

 private:
  FreeFlight flight_;
  double duration_;  // s; a touchdown after it is not this run's
};

// With flight the coin leaves the floor where N falls through zero: lift-off becomes a switch to a
// flight, read inside each step as the cone is (a hop shorter than a step shows no sign change). A
// cornered rim passing upright becomes the other corner's landing (docs/flight.md §4a).
template <int N>
void flightSwitches(std::vector<integrate::Event<N>>& events) {
  for (integrate::Event<N>& e : events) {
    if (e.id == static_cast<int>(ModelEvent::LiftOff)) {
      e.id = kLiftsOff;
      e.name = "lifts off";
      e.terminal = true;
      e.interiorChecks = kConeGrazeChecks;
    } else if (e.id == static_cast<int>(ModelEvent::CornerSwitch)) {
      e.id = kCornerLands;
      e.name = "corner lands";
    }
  }
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

bool belowUpright(const physics::CoinModel& model, const physics::FlightState& state) {
  return physics::kineticEnergy(model, state) + model.M * model.g * state.centre.y() < physics::uprightEnergy(model);
}

}  // namespace

HybridRun::HybridRun(const Simulation& simulation)
    : simulation_(simulation), pace_(0, simulation.solver.endTime, simulation.solver.maxSteps) {
  const physics::QuaternionState start = physics::fromEulerState(simulation.initial);
  const physics::Forward rolling = physics::forward(simulation_.model, start);
  const std::optional<physics::FlightState> flying = flightStart(simulation);
  // A coin that starts with too little energy to pass upright has its face decided before it moves.
  if (const physics::FlightState at = flying.value_or(flightStateOf(start, rolling));
      simulation.stopWhenDecided && belowUpright(simulation.model, at)) {
    ending_ = Ending{.event = ModelEvent::Decided, .t = 0, .state = at, .dissipated = 0};
  }
  if (flying) {
    startFlight(0, *flying, 0);
    return;
  }
  const Eigen::Vector3d rollingVelocity = rolling.velocity;
  const Eigen::Vector2d velocity =
      simulation.initialVelocity.value_or(Eigen::Vector2d(rollingVelocity.x(), rollingVelocity.z()));
  const physics::SlidingState sliding{.attitude = start, .slip = physics::slipOf(simulation_.model, start, velocity)};
  const physics::Forward slipping =
      physics::slidingForward(simulation_.model, sliding, simulation_.model.friction.kinetic, Eigen::Vector3d::UnitX());
  const physics::ContactMode mode = physics::startingMode(simulation_.model, rolling, slipping);
  if (mode == physics::ContactMode::Rolling) {
    startRolling(0, start, 0);
  } else {
    // A start off the rolling constraint is stated as the later switches are (issue 40).
    switches_.push_back({0, true});
    const physics::SlidingState fromZeroSlip{.attitude = start};
    startSliding(0, mode == physics::ContactMode::Sliding ? sliding : fromZeroSlip, 0, mode);
  }
}

HybridRun::~HybridRun() = default;

// N < 0 is never integrated as a contact here, whatever on_invalid says: the sliding law's friction
// -mu N s_hat would then push the coin along its slip and make energy (issue 40: +46 % in one
// scene). Until flight is modelled a sliding run ends at lift-off; on_invalid "warn" goes on past
// the rolling-only model's slip, which the sliding model replaces.
constexpr bool kLiftOffEndsTheRun = true;

void HybridRun::startRolling(double t, const physics::QuaternionState& state, double dissipated) {
  using Y = integrate::Vec<kRollingSize>;
  const physics::CoinModel model = holdingCorner(simulation_.model, state.q);
  const auto forward =
      remembering<kRollingSize>([model](const Y& y) { return physics::forward(model, rollingStateOf(y)); });
  std::vector<integrate::Event<kRollingSize>> events =
      validityEvents<Formulation::Quaternion, kRollingSize>(model, std::nullopt, kLiftOffEndsTheRun, forward);
  integrate::Event<kRollingSize> slides = switchEvent<kRollingSize>(
      kSlideOnset, "slides",
      [model, forward](double, const Y& y) { return physics::slideOnsetMargin(model, forward(y)); });
  slides.interiorChecks = kConeGrazeChecks;
  events.push_back(std::move(slides));
  if (simulation_.flight) flightSwitches(events);
  if (simulation_.stopWhenDecided) {
    events.push_back(decidedEvent<kRollingSize>(model, [forward](const Y& y) { return forward(y).energy; }));
  }
  Y y0;
  y0 << physics::toVector(state), dissipated;
  segment_ = std::make_unique<RollingSegment>(RollingKind{model}, t, y0, simulation_.solver,
                                              std::move(events), simulation_.duration);
}

void HybridRun::startSliding(double t, const physics::SlidingState& state, double dissipated,
                             physics::ContactMode mode) {
  using Y = integrate::Vec<kSlidingSize>;
  const physics::CoinModel model = holdingCorner(simulation_.model, state.attitude.q);
  const Eigen::Vector2d along = state.slip.norm() > 0 ? state.slip.normalized() : Eigen::Vector2d::UnitX();
  const SlidingRhs rhs{.model = model, .mode = mode, .direction = Eigen::Vector3d(along.x(), 0, along.y())};
  const auto forwardOf =
      remembering<kSlidingSize>([rhs](const Y& y) { return rhs.forward(y.head<physics::kSlidingStateSize>()); });
  std::vector<integrate::Event<kSlidingSize>> events = geometryEvents<kSlidingSize>(
      model, Formulation::Quaternion, [](const Y& y) { return physics::thetaOf(slidingStateOf(y).attitude.q); },
      [](const Y& y) {
        const physics::QuaternionState attitude = slidingStateOf(y).attitude;
        return tiltRate(attitude.q, attitude.omegaBody);
      });
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::LiftOff,
      [model, forwardOf](double, const Y& y) { return physics::liftOffMargin(model, forwardOf(y)); }, -1,
      kLiftOffEndsTheRun));
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::Painleve,
      [forwardOf](double, const Y& y) { return forwardOf(y).normalEffectiveMass - physics::kPainleveMargin; }, -1,
      true));
  const double resolvedSlip = kResolvedSlipPerAtol * simulation_.solver.atol;
  if (mode == physics::ContactMode::Sliding) {
    events.push_back(switchEvent<kSlidingSize>(kSlipStops, "rolls", [rhs, resolvedSlip](double at, const Y& y) {
      return physics::slipStopMargin(at, slidingStateOf(y).slip, slipRateOf(rhs, at, y), resolvedSlip);
    }));
    events.push_back(switchEvent<kSlidingSize>(kSlipCreeps, "creeps", [model, forwardOf](double, const Y& y) {
      return physics::slipCreepMargin(model, y.head<physics::kSlidingStateSize>(), forwardOf(y));
    }));
  } else {
    // Friction keeps to the rest while the slip passes zero, so the slip crosses it smoothly and its
    // length has a kink there that a step can jump: the stop is found on the slip along the rest.
    events.push_back(switchEvent<kSlidingSize>(kSlipStops, "rolls", [rhs, resolvedSlip](double at, const Y& y) {
      const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
      return physics::creepStopMargin(at, physics::toSlidingState(coin).slip, slipRateOf(rhs, at, y), resolvedSlip,
                                      rhs.frictionDirection(coin));
    }));
    events.push_back(switchEvent<kSlidingSize>(
        kSlipFrees, "slips freely",
        [rhs](double, const Y& y) {
          const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
          return physics::slipFreeMargin(rhs.model, coin, rhs.forward(coin));
        },
        +1));
  }
  if (simulation_.flight) flightSwitches(events);
  if (simulation_.stopWhenDecided) {
    events.push_back(decidedEvent<kSlidingSize>(model, [forwardOf](const Y& y) { return forwardOf(y).energy; }));
  }
  Y y0;
  y0 << physics::toVector(state), dissipated;
  segment_ = std::make_unique<SlidingSegment>(SlidingKind{rhs}, t, y0, simulation_.solver, std::move(events),
                                              simulation_.duration);
}

void HybridRun::startFlight(double t, const physics::FlightState& state, double dissipated) {
  segment_ = std::make_unique<FlightSegment>(simulation_.model, t, state, dissipated, simulation_.duration);
}

void HybridRun::startContact(double t, const physics::SlidingState& state, double dissipated) {
  const physics::CoinModel& model = simulation_.model;
  const physics::Forward rolling = physics::forward(model, state.attitude);
  const Eigen::Vector3d along = state.slip.norm() > 0 ? Eigen::Vector3d(state.slip.x(), 0, state.slip.y()).normalized()
                                                      : Eigen::Vector3d::UnitX();
  const physics::Forward slipping = physics::slidingForward(model, state, model.friction.kinetic, along);
  const physics::ContactMode mode = physics::startingMode(model, rolling, slipping);
  const physics::Forward& held = mode == physics::ContactMode::Rolling ? rolling : slipping;
  if (physics::liftOffMargin(model, held) <= 0) {
    startFlight(t, onTheFloor(model, flightStateOf(state.attitude, held)), dissipated);
    return;
  }
  if (mode == physics::ContactMode::Rolling) {
    startRolling(t, state.attitude, dissipated);
  } else {
    // A landing that slides is stated as the switches are, so every `rolls at` has its `slides at`.
    switches_.push_back({t, true});
    startSliding(t, mode == physics::ContactMode::Sliding ? state : physics::SlidingState{.attitude = state.attitude},
                 dissipated, mode);
  }
}

bool HybridRun::land(double t, const physics::FlightState& atTouch, double dissipated,
                     std::optional<Eigen::Vector3d> otherCorner) {
  std::size_t recent = 0;
  for (const ImpactRecord& impact : impacts_) recent += impact.t > t - 1 ? 1 : 0;
  const bool chattering = recent >= kMaxImpactsPerSecond;
  Landing landing = pipeline::land(simulation_, t, atTouch, dissipated, chattering);
  landing.impact.corner = otherCorner.has_value();
  impacts_.push_back(landing.impact);
  // The rocking between the corners has died away: both ends of the flat band rest on the floor, the
  // coin stands on its edge (docs/flight.md §4a).
  if (otherCorner && landing.next == Landing::Next::Contact) {
    const double still = restSpeed(simulation_.model);
    const Eigen::Vector3d landed = physics::lowestPointVector(simulation_.model, landing.state.q);
    const bool onBand = physics::pointVelocity(landing.state, landed).norm() < still &&
                        physics::pointVelocity(landing.state, *otherCorner).norm() < still;
    if (onBand || chattering) {
      ending_ = Ending{.event = ModelEvent::OnEdge, .t = t, .state = landing.state, .dissipated = landing.dissipated};
      return false;
    }
  }
  // An impact takes energy at once, so the fall below standing upright's is read here, not located.
  const bool decided = (landing.next == Landing::Next::Flight || landing.next == Landing::Next::Contact) &&
                       simulation_.stopWhenDecided && belowUpright(simulation_.model, landing.state);
  if (decided) {
    ending_ = Ending{.event = ModelEvent::Decided, .t = t, .state = landing.state, .dissipated = landing.dissipated};
    return false;
  }
  switch (landing.next) {
    case Landing::Next::Flight:
      startFlight(t, onTheFloor(simulation_.model, landing.state), landing.dissipated);
      return true;
    case Landing::Next::Contact:
      startContact(t, contactStateOf(simulation_.model, landing.state), landing.dissipated);
      return true;
    case Landing::Next::Rest:
    case Landing::Next::Jam:
      ending_ = Ending{.event = landing.next == Landing::Next::Rest ? ModelEvent::Rest : ModelEvent::ImpactJam,
                       .t = t,
                       .state = landing.state,
                       .dissipated = landing.dissipated};
      return false;
  }
  return false;
}

bool HybridRun::switchIfDue() {
  const std::optional<Handover> handover = segment_->handover();
  if (!handover) return false;
  // The finished segment's crossings gone past and its work, kept before it is replaced; the run's
  // pace is judged on all its segments' steps.
  const auto retire = [this, &handover] {
    const std::vector<RunEvent> crossings = segment_->warnings();
    warnings_.insert(warnings_.end(), crossings.begin(), crossings.end());
    finishedStats_ += segment_->stats();
    pace_.afterSteps(finishedStats_.acceptedSteps, handover->t);
  };
  // Past the limit the run ends: stick-slip, unless corner landings at upright come between the
  // switches. Then the switching is the flat band rocking on the floor as its landings accumulate
  // (docs/flight.md §4a; each landing leaves the rim sliding, then rolling), and its end is the
  // band's, on-edge. Stick-slip without the band has no corner landings at all; the band's rocking
  // makes at most two switches per landing.
  const auto tooManySwitches = [this, &handover](double t) {
    std::size_t recent = 0, cornerLandings = 0;
    for (const ModeSwitch& w : switches_) recent += w.t > t - 1 ? 1 : 0;
    if (recent < kMaxSwitchesPerSecond) return false;
    for (const ImpactRecord& impact : impacts_) cornerLandings += impact.corner && impact.t > t - 1 ? 1 : 0;
    if (3 * cornerLandings >= recent) {
      ending_ =
          Ending{.event = ModelEvent::OnEdge, .t = t, .state = handover->flight, .dissipated = handover->dissipated};
    } else {
      switchRefused_ = true;
    }
    return true;
  };
  const double t = handover->t, dissipated = handover->dissipated;
  const physics::SlidingState& state = handover->state;
  if (handover->id == kLiftsOff) {
    retire();
    startFlight(t, onTheFloor(simulation_.model, handover->flight), dissipated);
    return true;
  }
  if (handover->id == kTouchdown) {
    retire();
    return land(t, handover->flight, dissipated);
  }
  if (handover->id == kCornerLands) {
    retire();
    // The corner the tilt moves towards lands; the one the coin rolled on is the band's other end.
    const physics::FlightState& leaving = handover->flight;
    const double side = tiltRate(leaving.q, leaving.omegaBody) < 0 ? -1.0 : 1.0;
    physics::FlightState landing = leaving;
    landing.q = pastUpright(leaving.q, side);
    return land(t, onTheFloor(simulation_.model, landing), dissipated,
                physics::lowestPointVector(simulation_.model, pastUpright(leaving.q, -side)));
  }
  if (handover->id == kSlideOnset) {
    if (tooManySwitches(t)) return false;
    retire();
    switches_.push_back({t, true});
    startSliding(t, {.attitude = state.attitude}, dissipated, physics::ContactMode::Creeping);
    return true;
  }
  if (handover->id != kSlipStops) {
    retire();
    startSliding(t, state, dissipated,
                 handover->id == kSlipCreeps ? physics::ContactMode::Creeping : physics::ContactMode::Sliding);
    return true;
  }
  if (tooManySwitches(t)) return false;
  retire();
  const physics::Forward rolling = physics::forward(simulation_.model, state.attitude);
  // Friction takes the last stoppedSlip(t) of slip at once: the kinetic energy it removes is dissipated.
  const double afterStop = dissipated + (handover->forward.energy - rolling.energy);
  if (physics::modeAfterSlipStops(simulation_.model, rolling) == physics::ContactMode::Creeping) {
    startSliding(t, {.attitude = state.attitude}, afterStop, physics::ContactMode::Creeping);
    return true;
  }
  switches_.push_back({t, false});
  startRolling(t, state.attitude, afterStop);
  return true;
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
  if (segment_->handover() && !switchRefused_) return std::nullopt;
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
