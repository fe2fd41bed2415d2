#include "pipeline/coin_run.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "physics/observables.h"

namespace coinroll::pipeline {

namespace {

// rad. The quaternion carries no phi or psi: toEulerState recovers them modulo 2 pi and unwraps
// against the previous sample, which is right only while they turn by less than pi in between.
// Sampling the dense output every quarter turn keeps a factor 4 in hand for rates that grow
// within one such interval (they do near flat, like 1 / sqrt(cos theta)).
constexpr double kUnwrapTurn = std::numbers::pi / 4;

std::variant<CoinTrajectory, QuaternionTrajectory> startEither(const Simulation& simulation) {
  if (simulation.formulation == scene::Formulation::EulerAngles) return startTrajectory(simulation);
  return QuaternionTrajectory(QuaternionRhs{&simulation.model}, 0.0,
                              physics::toVector(physics::fromEulerState(simulation.initial)), simulation.solver,
                              quaternionValidityEvents(simulation.model, simulation.friction));
}

}  // namespace

std::vector<integrate::Event<physics::kQuaternionStateSize>> quaternionValidityEvents(const physics::CoinModel& model,
                                                                                      std::optional<double> friction) {
  using physics::QuaternionStateVec;
  using physics::toQuaternionState;
  std::vector<integrate::Event<physics::kQuaternionStateSize>> events;
  events.push_back({.name = "coin-flat",
                    .g = [](double, const QuaternionStateVec& y) { return physics::flatMargin(toQuaternionState(y)); },
                    .direction = -1});
  events.push_back({.name = "lift-off",
                    .g = [model](double, const QuaternionStateVec& y) {
                      return physics::liftOffMargin(model, toQuaternionState(y));
                    },
                    .direction = -1});
  if (friction) {
    const double mu = *friction;
    events.push_back({.name = "slip",
                      .g = [model, mu](double, const QuaternionStateVec& y) {
                        return physics::slipMargin(model, toQuaternionState(y), mu);
                      },
                      .direction = -1});
  }
  return events;
}

CoinRun::CoinRun(const Simulation& simulation)
    : trajectory_(startEither(simulation)), lastState_(simulation.initial) {}

std::optional<physics::CoinState> CoinRun::stateAt(double t) {
  if (auto* euler = std::get_if<CoinTrajectory>(&trajectory_)) {
    const std::optional<physics::StateVec> y = euler->stateAt(t);
    if (!y) return std::nullopt;
    return physics::toState(*y);
  }
  return quaternionStateAt(std::get<QuaternionTrajectory>(trajectory_), t);
}

std::optional<physics::CoinState> CoinRun::quaternionStateAt(QuaternionTrajectory& trajectory, double t) {
  if (t < lastTime_) {
    throw std::logic_error(fmt::format("CoinRun::stateAt: queries must not go back in time ({} after {})", t, lastTime_));
  }
  while (lastTime_ < t) {
    const double turnRate = std::max(std::abs(physics::precessionRate(lastState_)), std::abs(physics::spinRate(lastState_)));
    const double next = turnRate > 0 ? std::min(t, lastTime_ + kUnwrapTurn / turnRate) : t;
    const std::optional<physics::QuaternionStateVec> y = trajectory.stateAt(next);
    if (!y) return std::nullopt;
    lastState_ = physics::toEulerState(physics::toQuaternionState(*y), lastState_);
    lastTime_ = next;
  }
  return lastState_;
}

std::optional<integrate::EventHit<physics::kStateSize>> CoinRun::stoppedBy() const {
  if (const auto* euler = std::get_if<CoinTrajectory>(&trajectory_)) return euler->stoppedBy();
  const auto& hit = std::get<QuaternionTrajectory>(trajectory_).stoppedBy();
  if (!hit) return std::nullopt;
  // The hit lies within one unwrap interval of the last sample, so lastState_ continues it.
  const physics::CoinState s = physics::toEulerState(physics::toQuaternionState(hit->y), lastState_);
  return integrate::EventHit<physics::kStateSize>{hit->name, hit->t, physics::toVector(s)};
}

integrate::Stats CoinRun::stats() const {
  return std::visit([](const auto& trajectory) { return trajectory.stats(); }, trajectory_);
}

}  // namespace coinroll::pipeline
