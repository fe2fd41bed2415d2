#include "pipeline/hybrid_run.h"

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
constexpr int kSlipStops = 1001;   // sliding: the slip speed falls to kStoppedSlip

// m/s. Sliding ends when the slip speed falls to this, not to 0, where friction's direction is no
// longer defined: the last 1e-12 m/s is closed by friction at once, its kinetic energy booked as
// dissipated (docs/sliding.md §4), and the switch lands about 1e-13 s early for a slip that
// decelerates at mu g.
constexpr double kStoppedSlip = 1e-12;

// Stick-slip: more switches than this within one simulated second end the run (docs/sliding.md §4).
constexpr std::size_t kMaxSwitchesPerSecond = 1000;

struct SlidingRhs {
  physics::CoinModel model;
  double mu = 0;
  Eigen::Vector3d direction;  // s_hat while the slip is below round-off

  integrate::Vec<kSlidingSize> operator()(double /*t*/, const integrate::Vec<kSlidingSize>& y) const {
    const physics::SlidingRates r =
        physics::slidingRates(model, y.head<physics::kSlidingStateSize>(), mu, direction);
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

// Unit, horizontal, opposite to the rolling friction force: the slip direction the contract takes
// at the switch (docs/sliding.md §4).
Eigen::Vector3d againstRollingFriction(const physics::Forward& rolling) {
  const Eigen::Vector3d friction(rolling.reaction.R.x(), 0, rolling.reaction.R.z());
  const double size = friction.norm();
  return size > 0 ? Eigen::Vector3d(-friction / size) : Eigen::Vector3d::UnitX();
}

template <int N>
integrate::Event<N> switchEvent(int id, const char* name, std::function<double(double, const integrate::Vec<N>&)> g) {
  return {.name = name, .id = id, .g = std::move(g), .direction = -1, .terminal = true};
}

}  // namespace

struct HybridRun::Segment {
  std::variant<RollingTrajectory, SlidingTrajectory> trajectory;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // sliding: s_hat at the segment's start
};

HybridRun::HybridRun(const Simulation& simulation) : simulation_(simulation) {
  const physics::QuaternionState start = physics::fromEulerState(simulation.initial);
  const physics::Forward rolling = physics::forward(simulation_.model, start);
  const Eigen::Vector3d rollingVelocity = rolling.velocity;
  const Eigen::Vector2d velocity = simulation.initialVelocity.value_or(Eigen::Vector2d(rollingVelocity.x(), rollingVelocity.z()));
  const physics::SlidingState sliding{.attitude = start, .slip = physics::slipOf(simulation_.model, start, velocity)};
  const physics::Forward slipping = physics::slidingForward(simulation_.model, sliding, simulation.kineticFriction, Eigen::Vector3d::UnitX());
  if (slipping.slip.norm() > kStoppedSlip) {
    startSliding(0, sliding, 0, slipping.slip.normalized());
  } else if (physics::slipMargin(simulation_.model, rolling, *simulation.friction) < 0) {
    startSliding(0, sliding, 0, againstRollingFriction(rolling));
  } else {
    startRolling(0, start, 0);
  }
}

HybridRun::~HybridRun() = default;
HybridRun::HybridRun(HybridRun&&) noexcept = default;
HybridRun& HybridRun::operator=(HybridRun&&) noexcept = default;

void HybridRun::startRolling(double t, const physics::QuaternionState& state, double dissipated) {
  using Y = integrate::Vec<kRollingSize>;
  std::vector<integrate::Event<kRollingSize>> events =
      validityEvents<Formulation::Quaternion, kRollingSize>(simulation_.model, std::nullopt, simulation_.validityIsTerminal);
  events.push_back(switchEvent<kRollingSize>(
      kSlideOnset, "slides", [model = simulation_.model, mu = *simulation_.friction](double, const Y& y) {
        return physics::slipMargin(model, physics::forward(model, rollingStateOf(y)), mu);
      }));
  Y y0;
  y0 << physics::toVector(state), dissipated;
  segment_ = std::make_unique<Segment>(Segment{
      .trajectory = RollingTrajectory(physics::CoinRhs<Formulation::Quaternion>{simulation_.model}, t, y0, simulation_.solver, events),
      .direction = Eigen::Vector3d::UnitX()});
}

void HybridRun::startSliding(double t, const physics::SlidingState& state, double dissipated, const Eigen::Vector3d& slipDirection) {
  using Y = integrate::Vec<kSlidingSize>;
  const double mu = simulation_.kineticFriction;
  const auto forwardOf = [model = simulation_.model, mu, slipDirection](const Y& y) {
    return physics::slidingForward(model, slidingStateOf(y), mu, slipDirection);
  };
  std::vector<integrate::Event<kSlidingSize>> events = geometryEvents<kSlidingSize>(
      simulation_.model, Formulation::Quaternion, [](const Y& y) { return physics::thetaOf(slidingStateOf(y).attitude.q); });
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::LiftOff, [model = simulation_.model, forwardOf](double, const Y& y) { return physics::liftOffMargin(model, forwardOf(y)); },
      -1, simulation_.validityIsTerminal));
  events.push_back(modelEvent<kSlidingSize>(
      ModelEvent::Painleve, [forwardOf](double, const Y& y) { return forwardOf(y).normalEffectiveMass; }, -1, true));
  events.push_back(switchEvent<kSlidingSize>(
      kSlipStops, "rolls", [forwardOf](double, const Y& y) { return forwardOf(y).slip.norm() - kStoppedSlip; }));
  Y y0;
  y0 << physics::toVector(state), dissipated;
  segment_ = std::make_unique<Segment>(Segment{
      .trajectory = SlidingTrajectory(SlidingRhs{simulation_.model, mu, slipDirection}, t, y0, simulation_.solver, events),
      .direction = slipDirection});
}

// The seed's variables, the forward pass of the segment's mode and the dissipated energy of an
// integrated state of either kind.
HybridSample sampleOf(const physics::CoinModel& model, double /*mu*/, const Eigen::Vector3d& /*direction*/,
                      const integrate::Vec<kRollingSize>& y, const physics::CoinState& continuation) {
  const physics::QuaternionState state = rollingStateOf(y);
  return {physics::toEulerState(state, continuation), physics::forward(model, state), y[kRollingSize - 1]};
}

HybridSample sampleOf(const physics::CoinModel& model, double mu, const Eigen::Vector3d& direction,
                      const integrate::Vec<kSlidingSize>& y, const physics::CoinState& continuation) {
  const physics::SlidingState state = slidingStateOf(y);
  return {physics::toEulerState(state.attitude, continuation), physics::slidingForward(model, state, mu, direction),
          y[kSlidingSize - 1]};
}

bool HybridRun::switchIfDue() {
  const double mu = simulation_.kineticFriction;
  const Eigen::Vector3d direction = segment_->direction;
  // The finished segment's crossings gone past and its work, kept before it is replaced.
  const auto retire = [&](const auto& trajectory) {
    for (const auto& crossing : trajectory.nonTerminalHits()) {
      const HybridSample at = sampleOf(simulation_.model, mu, direction, crossing.y, physics::CoinState{});
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
    const physics::Forward f = physics::forward(simulation_.model, state);
    const double t = hit->t, dissipated = hit->y[kRollingSize - 1];
    retire(*rolling);
    switches_.push_back({t, true});
    startSliding(t, {.attitude = state, .slip = Eigen::Vector2d::Zero()}, dissipated, againstRollingFriction(f));
    return true;
  }
  auto& sliding = std::get<SlidingTrajectory>(segment_->trajectory);
  const auto& hit = sliding.stoppedBy();
  if (!hit || hit->id != kSlipStops) return false;
  if (tooManySwitches(hit->t)) return false;
  const physics::SlidingState state = slidingStateOf(hit->y);
  const double t = hit->t;
  const physics::Forward slipping = physics::slidingForward(simulation_.model, state, mu, direction);
  retire(sliding);
  const physics::Forward rolling = physics::forward(simulation_.model, state.attitude);
  // Friction takes the last kStoppedSlip of slip at once: the kinetic energy it removes is dissipated.
  const double dissipated = hit->y[kSlidingSize - 1] + (slipping.energy - rolling.energy);
  if (physics::slipMargin(simulation_.model, rolling, *simulation_.friction) < 0) {
    // At zero slip the rolling reaction does not fit the cone: the coin slides on, from zero slip
    // along the direction the contract gives at a switch.
    startSliding(t, {.attitude = state.attitude, .slip = Eigen::Vector2d::Zero()}, dissipated, againstRollingFriction(rolling));
    return true;
  }
  switches_.push_back({t, false});
  startRolling(t, state.attitude, dissipated);
  return true;
}

std::optional<HybridSample> HybridRun::sampleAt(double t, const physics::CoinState& continuation) {
  for (;;) {
    const std::optional<HybridSample> sample = std::visit(
        [&](auto& trajectory) -> std::optional<HybridSample> {
          const auto y = trajectory.stateAt(t);
          if (!y) return std::nullopt;
          return sampleOf(simulation_.model, simulation_.kineticFriction, segment_->direction, *y, continuation);
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
        const HybridSample at = sampleOf(simulation_.model, simulation_.kineticFriction, segment_->direction, hit->y, continuation);
        // A switch the run could not make (stick-slip past its bound) ends it as stick-slip.
        const bool modelEvent = hit->id != kSlideOnset && hit->id != kSlipStops;
        return RunEvent{modelEvent ? static_cast<ModelEvent>(hit->id) : ModelEvent::StickSlip, hit->t, at.state, at.forward,
                        at.dissipated};
      },
      segment_->trajectory);
}

std::vector<RunEvent> HybridRun::warnings() const {
  std::vector<RunEvent> all = warnings_;
  std::visit(
      [&](const auto& trajectory) {
        for (const auto& crossing : trajectory.nonTerminalHits()) {
          if (crossing.t > simulation_.duration) break;
          const HybridSample at = sampleOf(simulation_.model, simulation_.kineticFriction, segment_->direction, crossing.y, physics::CoinState{});
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
