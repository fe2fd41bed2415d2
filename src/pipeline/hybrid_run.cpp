#include "pipeline/hybrid_run.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

#include "pipeline/validity_events.h"

namespace coinroll::pipeline {

namespace {

using physics::Formulation;
using physics::ModelEvent;

constexpr int kRollingSize = physics::kQuaternionStateSize + 1;  // with the dissipated energy
constexpr int kSlidingSize = physics::kSlidingStateSize + 1;

// The switches' event ids, past ModelEvent's values.
constexpr int kSlideOnset = 1000;  // rolling: the reaction reaches the cone
constexpr int kSlipStops = 1001;   // sliding: the slip speed falls to stoppedSlip(t)
constexpr int kSlipFrees = 1002;   // creeping: the slip's direction is slow enough to integrate
constexpr int kSlipCreeps = 1003;  // sliding: the slip's direction is too fast to integrate

// m/s. Sliding ends when the slip speed falls to this, not to 0, where friction's direction is no
// longer defined: the last of the slip is closed by friction at once, its kinetic energy booked as
// dissipated (docs/sliding.md §4.5). A free slip's direction turns at restoring / |s|, so the steps
// near the stop shrink with |s|; the stop must come while they are still above the integrator's
// floor of 1e-14 |t|, hence a threshold growing with t (10^-11 m/s up to 1 s: a skid switches about
// 3e-12 s early at mu g = 3 m/s^2; at 1e-12 m/s a skid at t = 4.8 s stalled).
double stoppedSlip(double t) { return 1e-11 * std::max(1.0, std::abs(t)); }

// Stick-slip: more switches than this within one simulated second end the run (docs/sliding.md §4).
constexpr std::size_t kMaxSwitchesPerSecond = 1000;

// rad: the creeping slip's direction lags its rest by at most this before it is integrated freely
// (docs/sliding.md §4.6): the lag is (turn rate of the rest) |s| / restoring.
constexpr double kCreepLag = 1e-3;
// rad: a free slip is handed back to its rest only within this angle of it (docs/sliding.md §4.6).
constexpr double kCreepAlignment = 1e-5;

struct SlidingRhs {
  physics::CoinModel model;
  double mu = 0;
  SlipMode mode = SlipMode::Free;
  Eigen::Vector3d direction;  // free: s_hat while the slip is below round-off

  // Creeping: along the rest, searched from the segment's direction where rolling leaves every
  // direction neutral (a trial state past zero slip must not flip friction with it, or the slip's
  // stop is never crossed); where a trial state has no rest, along the slip itself, as when free.
  Eigen::Vector3d frictionDirection(const physics::SlidingStateVec& y) const {
    if (const std::optional<physics::Creep> creep = physics::findCreep(model, y, mu, direction)) return creep->slipHat;
    const Eigen::Vector2d slip = y.tail<2>();
    return slip.norm() > physics::kSlipRoundOff ? Eigen::Vector3d(slip.x() / slip.norm(), 0, slip.y() / slip.norm())
                                                : direction;
  }
  physics::Forward forward(const physics::SlidingStateVec& y) const {
    const physics::SlidingState state = physics::toSlidingState(y);
    return mode == SlipMode::Free ? physics::slidingForward(model, state, mu, direction)
                                  : physics::slidingForwardAlong(model, state, mu, frictionDirection(y));
  }
  integrate::Vec<kSlidingSize> operator()(double /*t*/, const integrate::Vec<kSlidingSize>& y) const {
    const physics::SlidingStateVec& coin = y.head<physics::kSlidingStateSize>();
    const physics::SlidingRates r = mode == SlipMode::Free
                                        ? physics::slidingRates(model, coin, mu, direction)
                                        : physics::slidingRatesAlong(model, coin, mu, frictionDirection(coin));
    integrate::Vec<kSlidingSize> dy;
    dy << r.dy, r.power;
    return dy;
  }
};

using RollingTrajectory = integrate::Trajectory<kRollingSize, physics::CoinRhs<Formulation::Quaternion>>;
using SlidingTrajectory = integrate::Trajectory<kSlidingSize, SlidingRhs>;

physics::SlidingState slidingStateOf(const integrate::Vec<kSlidingSize>& y) {
  return physics::toSlidingState(y.head<physics::kSlidingStateSize>());
}

physics::QuaternionState rollingStateOf(const integrate::Vec<kRollingSize>& y) {
  return physics::toQuaternionState(y.head<physics::kQuaternionStateSize>());
}

// m/s: the slip speed above which its direction is integrated (kCreepLag); the rest turns with the
// fastest of the body's rotation, the contact's precession and the rocking rate sqrt(g/a).
double freeSlipSpeed(const physics::CoinModel& model, const physics::Forward& f, double restoring) {
  const double turnRate = std::max({f.omega.norm(), std::abs(f.precessionRate), std::sqrt(model.g / model.a)});
  return kCreepLag * std::max(restoring, 0.0) / turnRate;
}

template <int N>
integrate::Event<N> switchEvent(int id, const char* name, std::function<double(double, const integrate::Vec<N>&)> g,
                                int direction = -1) {
  return {.name = name, .id = id, .g = std::move(g), .direction = direction, .terminal = true};
}

}  // namespace

struct HybridRun::Segment {
  std::variant<RollingTrajectory, SlidingTrajectory> trajectory;
  SlidingRhs sliding;  // the sliding segment's right-hand side, for its samples
};

HybridRun::HybridRun(const Simulation& simulation) : simulation_(simulation) {
  const physics::QuaternionState start = physics::fromEulerState(simulation.initial);
  const physics::Forward rolling = physics::forward(simulation_.model, start);
  const Eigen::Vector3d rollingVelocity = rolling.velocity;
  const Eigen::Vector2d velocity =
      simulation.initialVelocity.value_or(Eigen::Vector2d(rollingVelocity.x(), rollingVelocity.z()));
  const physics::SlidingState sliding{.attitude = start, .slip = physics::slipOf(simulation_.model, start, velocity)};
  const physics::Forward slipping =
      physics::slidingForward(simulation_.model, sliding, simulation.kineticFriction, Eigen::Vector3d::UnitX());
  if (slipping.slip.norm() > stoppedSlip(0)) {
    startSliding(0, sliding, 0, SlipMode::Free);
  } else if (physics::slipMargin(simulation_.model, rolling, *simulation.friction) < 0) {
    startSliding(0, {.attitude = start}, 0, SlipMode::Creeping);
  } else {
    startRolling(0, start, 0);
  }
}

HybridRun::~HybridRun() = default;
HybridRun::HybridRun(HybridRun&&) noexcept = default;
HybridRun& HybridRun::operator=(HybridRun&&) noexcept = default;

// N < 0 is never integrated as a contact here, whatever on_invalid says: the sliding law's friction
// -mu N s_hat would then push the coin along its slip and make energy (issue 40: +46 % in one
// scene). Until flight is modelled a sliding run ends at lift-off; on_invalid "warn" goes on past
// the rolling-only model's slip, which the sliding model replaces.
constexpr bool kLiftOffEndsTheRun = true;

void HybridRun::startRolling(double t, const physics::QuaternionState& state, double dissipated) {
  using Y = integrate::Vec<kRollingSize>;
  std::vector<integrate::Event<kRollingSize>> events =
      validityEvents<Formulation::Quaternion, kRollingSize>(simulation_.model, std::nullopt, kLiftOffEndsTheRun);
  integrate::Event<kRollingSize> slides = switchEvent<kRollingSize>(
      kSlideOnset, "slides", [model = simulation_.model, mu = *simulation_.friction](double, const Y& y) {
        return physics::slipMargin(model, physics::forward(model, rollingStateOf(y)), mu);
      });
  slides.interiorChecks = kConeGrazeChecks;
  events.push_back(std::move(slides));
  Y y0;
  y0 << physics::toVector(state), dissipated;
  segment_ = std::make_unique<Segment>(
      Segment{.trajectory = RollingTrajectory(physics::CoinRhs<Formulation::Quaternion>{simulation_.model}, t, y0,
                                              simulation_.solver, events),
              .sliding = {}});
}

void HybridRun::startSliding(double t, const physics::SlidingState& state, double dissipated, SlipMode mode) {
  using Y = integrate::Vec<kSlidingSize>;
  const physics::CoinModel& model = simulation_.model;
  const double mu = simulation_.kineticFriction;
  const Eigen::Vector2d along = state.slip.norm() > 0 ? state.slip.normalized() : Eigen::Vector2d::UnitX();
  const SlidingRhs rhs{.model = model, .mu = mu, .mode = mode, .direction = Eigen::Vector3d(along.x(), 0, along.y())};
  const auto forwardOf = [rhs](const Y& y) { return rhs.forward(y.head<physics::kSlidingStateSize>()); };
  std::vector<integrate::Event<kSlidingSize>> events = geometryEvents<kSlidingSize>(
      model, Formulation::Quaternion, [](const Y& y) { return physics::thetaOf(slidingStateOf(y).attitude.q); });
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::LiftOff,
      [model, forwardOf](double, const Y& y) { return physics::liftOffMargin(model, forwardOf(y)); }, -1,
      kLiftOffEndsTheRun));
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::Painleve,
      [forwardOf](double, const Y& y) { return forwardOf(y).normalEffectiveMass - physics::kPainleveMargin; }, -1,
      true));
  if (mode == SlipMode::Free) {
    events.push_back(switchEvent<kSlidingSize>(
        kSlipStops, "rolls", [](double at, const Y& y) { return slidingStateOf(y).slip.norm() - stoppedSlip(at); }));
    // A slip that falls back to half the creep's threshold hands its direction to its rest, once it
    // has come to the rest: the threshold fades to zero as the slip's angle from the rest grows to
    // kCreepLag, so a slide that ends across the rest's pull (a skid) is integrated to its end.
    events.push_back(switchEvent<kSlidingSize>(kSlipCreeps, "creeps", [model, mu, forwardOf](double, const Y& y) {
      const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
      const Eigen::Vector2d slip = physics::toSlidingState(coin).slip;
      const std::optional<physics::Creep> creep = physics::findCreep(model, coin, mu);
      if (!creep) return slip.norm();
      const Eigen::Vector2d rest(creep->slipHat.x(), creep->slipHat.z());
      const double angleFromRest = std::acos(std::clamp(rest.dot(slip.normalized()), -1.0, 1.0));
      const double nearness = std::max(0.0, 1 - angleFromRest / kCreepAlignment);
      return slip.norm() - 0.5 * nearness * freeSlipSpeed(model, forwardOf(y), creep->restoring);
    }));
  } else {
    // Friction keeps to the rest while the slip passes zero, so the slip crosses it smoothly and its
    // length has a kink there that a step can jump: the stop is found on the slip along the rest.
    events.push_back(switchEvent<kSlidingSize>(kSlipStops, "rolls", [rhs](double at, const Y& y) {
      const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
      const Eigen::Vector3d rest = rhs.frictionDirection(coin);
      const Eigen::Vector2d slip = physics::toSlidingState(coin).slip;
      return slip.x() * rest.x() + slip.y() * rest.z() - stoppedSlip(at);
    }));
    events.push_back(switchEvent<kSlidingSize>(
        kSlipFrees, "slips freely",
        [rhs](double, const Y& y) {
          const physics::SlidingStateVec coin = y.head<physics::kSlidingStateSize>();
          return physics::toSlidingState(coin).slip.norm() -
                 freeSlipSpeed(rhs.model, rhs.forward(coin),
                               physics::findCreep(rhs.model, coin, rhs.mu).value_or(physics::Creep{}).restoring);
        },
        +1));
  }
  Y y0;
  y0 << physics::toVector(state), dissipated;
  segment_ = std::make_unique<Segment>(
      Segment{.trajectory = SlidingTrajectory(rhs, t, y0, simulation_.solver, events), .sliding = rhs});
}

// The seed's variables, the forward pass of the segment's mode and the dissipated energy of an
// integrated state of either kind.
HybridSample sampleOf(const physics::CoinModel& model, const SlidingRhs& /*sliding*/,
                      const integrate::Vec<kRollingSize>& y, const physics::CoinState& continuation) {
  const physics::QuaternionState state = rollingStateOf(y);
  return {physics::toEulerState(state, continuation), physics::forward(model, state), y[kRollingSize - 1]};
}

HybridSample sampleOf(const physics::CoinModel& /*model*/, const SlidingRhs& sliding,
                      const integrate::Vec<kSlidingSize>& y, const physics::CoinState& continuation) {
  return {physics::toEulerState(slidingStateOf(y).attitude, continuation),
          sliding.forward(y.head<physics::kSlidingStateSize>()), y[kSlidingSize - 1]};
}

bool HybridRun::switchIfDue() {
  const SlidingRhs sliding = segment_->sliding;
  // The finished segment's crossings gone past and its work, kept before it is replaced.
  const auto retire = [&](const auto& trajectory) {
    for (const auto& crossing : trajectory.nonTerminalHits()) {
      const HybridSample at = sampleOf(simulation_.model, sliding, crossing.y, physics::CoinState{});
      warnings_.push_back({static_cast<ModelEvent>(crossing.id), crossing.t, at.state, at.forward, at.dissipated});
    }
    const integrate::Stats work = trajectory.stats();
    finishedStats_.rhsEvaluations += work.rhsEvaluations;
    finishedStats_.acceptedSteps += work.acceptedSteps;
    finishedStats_.rejectedSteps += work.rejectedSteps;
  };
  const auto tooManySwitches = [this](double t) {
    std::size_t recent = 0;
    for (const ModeSwitch& w : switches_) recent += w.t > t - 1 ? 1 : 0;
    return recent >= kMaxSwitchesPerSecond;
  };
  if (auto* rolling = std::get_if<RollingTrajectory>(&segment_->trajectory)) {
    const auto& hit = rolling->stoppedBy();
    if (!hit || hit->id != kSlideOnset) return false;
    if (tooManySwitches(hit->t)) return false;
    const physics::QuaternionState state = rollingStateOf(hit->y);
    const double t = hit->t, dissipated = hit->y[kRollingSize - 1];
    retire(*rolling);
    switches_.push_back({t, true});
    startSliding(t, {.attitude = state}, dissipated, SlipMode::Creeping);
    return true;
  }
  auto& trajectory = std::get<SlidingTrajectory>(segment_->trajectory);
  const auto& hit = trajectory.stoppedBy();
  if (!hit || (hit->id != kSlipStops && hit->id != kSlipCreeps && hit->id != kSlipFrees)) return false;
  const physics::SlidingState state = slidingStateOf(hit->y);
  const double t = hit->t, dissipated = hit->y[kSlidingSize - 1];
  if (hit->id != kSlipStops) {
    retire(trajectory);
    startSliding(t, state, dissipated, hit->id == kSlipCreeps ? SlipMode::Creeping : SlipMode::Free);
    return true;
  }
  if (tooManySwitches(t)) return false;
  const physics::Forward slipping = sliding.forward(hit->y.head<physics::kSlidingStateSize>());
  retire(trajectory);
  const physics::Forward rolling = physics::forward(simulation_.model, state.attitude);
  // Friction takes the last stoppedSlip(t) of slip at once: the kinetic energy it removes is dissipated.
  const double afterStop = dissipated + (slipping.energy - rolling.energy);
  if (physics::slipMargin(simulation_.model, rolling, *simulation_.friction) < 0) {
    // At zero slip the rolling reaction does not fit the cone: the coin slides on from zero slip,
    // its direction at its rest.
    startSliding(t, {.attitude = state.attitude}, afterStop, SlipMode::Creeping);
    return true;
  }
  switches_.push_back({t, false});
  startRolling(t, state.attitude, afterStop);
  return true;
}

std::optional<HybridSample> HybridRun::sampleAt(double t, const physics::CoinState& continuation) {
  for (;;) {
    const std::optional<HybridSample> sample = std::visit(
        [&](auto& trajectory) -> std::optional<HybridSample> {
          const auto y = trajectory.stateAt(t);
          if (!y) return std::nullopt;
          return sampleOf(simulation_.model, segment_->sliding, *y, continuation);
        },
        segment_->trajectory);
    if (sample) return sample;
    if (!switchIfDue()) return std::nullopt;
  }
}

std::optional<RunEvent> HybridRun::stoppedBy(const physics::CoinState& continuation) const {
  return std::visit(
      [&](const auto& trajectory) -> std::optional<RunEvent> {
        const auto& hit = trajectory.stoppedBy();
        if (!hit || hit->t > simulation_.duration) return std::nullopt;
        const HybridSample at = sampleOf(simulation_.model, segment_->sliding, hit->y, continuation);
        // A switch the run could not make (stick-slip past its bound) ends it as stick-slip.
        const bool modelEvent = hit->id < kSlideOnset;
        return RunEvent{modelEvent ? static_cast<ModelEvent>(hit->id) : ModelEvent::StickSlip, hit->t, at.state,
                        at.forward, at.dissipated};
      },
      segment_->trajectory);
}

std::vector<RunEvent> HybridRun::warnings() const {
  std::vector<RunEvent> all = warnings_;
  std::visit(
      [&](const auto& trajectory) {
        for (const auto& crossing : trajectory.nonTerminalHits()) {
          if (crossing.t > simulation_.duration) break;
          const HybridSample at = sampleOf(simulation_.model, segment_->sliding, crossing.y, physics::CoinState{});
          all.push_back({static_cast<ModelEvent>(crossing.id), crossing.t, at.state, at.forward, at.dissipated});
        }
      },
      segment_->trajectory);
  return all;
}

integrate::Stats HybridRun::stats() const {
  integrate::Stats total = finishedStats_;
  std::visit(
      [&total](const auto& trajectory) {
        const integrate::Stats work = trajectory.stats();
        total.rhsEvaluations += work.rhsEvaluations;
        total.acceptedSteps += work.acceptedSteps;
        total.rejectedSteps += work.rejectedSteps;
      },
      segment_->trajectory);
  return total;
}

}  // namespace coinroll::pipeline
