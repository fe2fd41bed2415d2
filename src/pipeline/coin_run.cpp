#include "pipeline/coin_run.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include "physics/observables.h"
#include "pipeline/cancelled.h"
#include "pipeline/validity_events.h"

namespace coinroll::pipeline {

namespace {

using physics::Formulation;

// rad. The quaternion carries no phi or psi: toEulerState recovers them modulo 2 pi and unwraps
// against the previous sample, which is right only while they turn by less than pi in between.
// Sampling the dense output every quarter turn keeps a factor 4 in hand for rates that grow
// within one such interval (they do near flat, like 1 / sqrt(cos theta)).
constexpr double kUnwrapTurn = std::numbers::pi / 4;

template <Formulation F, int N>
integrate::Trajectory<N, physics::CoinRhs<F>> start(const Simulation& simulation) {
  integrate::Vec<N> y0;
  if constexpr (F == Formulation::EulerAngles) {
    y0.template head<physics::kStateSize>() = physics::toVector(simulation.initial);
  } else {
    y0.template head<physics::kQuaternionStateSize>() = physics::toVector(physics::fromEulerState(simulation.initial));
  }
  if constexpr (N > physics::kMotionSize<F>) y0[N - 1] = 0;  // nothing dissipated yet
  return {physics::CoinRhs<F>{simulation.model}, 0.0, y0, simulation.solver,
          validityEvents<F, N>(simulation.model, simulation.friction, simulation.validityIsTerminal)};
}

template <class Variant>
Variant startEither(const Simulation& simulation) {
  if (simulation.sliding) return Variant(std::in_place_type<HybridRun>, simulation);
  const bool dissipative = !simulation.model.effects.empty();
  if (simulation.formulation == Formulation::EulerAngles) {
    if (dissipative) return start<Formulation::EulerAngles, physics::kStateSize + 1>(simulation);
    return start<Formulation::EulerAngles, physics::kStateSize>(simulation);
  }
  if (dissipative) return start<Formulation::Quaternion, physics::kQuaternionStateSize + 1>(simulation);
  return start<Formulation::Quaternion, physics::kQuaternionStateSize>(simulation);
}

template <Formulation F, int N>
double dissipatedOf(const integrate::Vec<N>& y) {
  if constexpr (N > physics::kMotionSize<F>) return y[N - 1];
  else return 0;
}

template <class T>
struct RunTraits;

template <class T>
inline constexpr bool kHybrid = std::is_same_v<std::decay_t<T>, HybridRun>;

template <int N, Formulation F>
struct RunTraits<integrate::Trajectory<N, physics::CoinRhs<F>>> {
  static constexpr Formulation kFormulation = F;
  static constexpr int kSize = N;
};

}  // namespace

CoinRun::CoinRun(const Simulation& simulation)
    : trajectory_(startEither<decltype(trajectory_)>(simulation)), lastState_(simulation.initial),
      model_(simulation.model), cancel_(simulation.cancel), duration_(simulation.duration) {}

std::optional<RunSample> CoinRun::sampleAt(double t) {
  throwIfCancelled(cancel_);
  return std::visit(
      [this, t](auto& run) {
        if constexpr (kHybrid<decltype(run)>) {
          return hybridSampleAt(run, t);
        } else {
          using Traits = RunTraits<std::decay_t<decltype(run)>>;
          return sampleOf<Traits::kFormulation, Traits::kSize>(run, t);
        }
      },
      trajectory_);
}

std::optional<RunSample> CoinRun::hybridSampleAt(HybridRun& run, double t) {
  if (t < lastTime_) {
    throw std::logic_error(
        fmt::format("CoinRun::stateAt: queries must not go back in time ({} after {})", t, lastTime_));
  }
  // As for the quaternion formulation (sampleOf): phi and psi unwrapped every quarter turn.
  while (lastTime_ < t || !lastForwardValid_) {
    throwIfCancelled(cancel_);
    const double turnRate = std::max(std::abs(lastForward_.precessionRate), std::abs(lastForward_.spinRate));
    const double next = lastForwardValid_ && turnRate > 0 ? std::min(t, lastTime_ + kUnwrapTurn / turnRate) : t;
    const std::optional<HybridSample> sample = run.sampleAt(next, lastState_);
    if (!sample) return std::nullopt;
    lastState_ = sample->state;
    lastForward_ = sample->forward;
    lastDissipated_ = sample->dissipated;
    lastTime_ = next;
    lastForwardValid_ = true;
  }
  return RunSample{lastState_, lastForward_, lastDissipated_};
}

std::optional<physics::CoinState> CoinRun::stateAt(double t) {
  const std::optional<RunSample> sample = sampleAt(t);
  if (!sample) return std::nullopt;
  return sample->state;
}

template <Formulation F, int N>
std::optional<RunSample> CoinRun::sampleOf(Run<F, N>& run, double t) {
  if constexpr (F == Formulation::EulerAngles) {
    const std::optional<integrate::Vec<N>> y = run.stateAt(t);
    if (!y) return std::nullopt;
    return RunSample{seedState<F, N>(*y), forwardOf<F, N>(model_, *y), dissipatedOf<F, N>(*y)};
  } else {
    if (t < lastTime_) {
      throw std::logic_error(
          fmt::format("CoinRun::stateAt: queries must not go back in time ({} after {})", t, lastTime_));
    }
    bool moved = false;
    std::optional<integrate::Vec<N>> y;
    while (lastTime_ < t) {
      throwIfCancelled(cancel_);
      const double turnRate =
          std::max(std::abs(physics::precessionRate(lastState_)), std::abs(physics::spinRate(lastState_)));
      const double next = turnRate > 0 ? std::min(t, lastTime_ + kUnwrapTurn / turnRate) : t;
      y = run.stateAt(next);
      if (!y) return std::nullopt;
      lastState_ = seedState<F, N>(*y, lastState_);
      lastDissipated_ = dissipatedOf<F, N>(*y);
      lastTime_ = next;
      moved = true;
    }
    if (moved) {
      lastForward_ = forwardOf<F, N>(model_, *y);
    } else if (!lastForwardValid_) {
      const std::optional<integrate::Vec<N>> now = run.stateAt(lastTime_);
      if (!now) return std::nullopt;
      lastForward_ = forwardOf<F, N>(model_, *now);
    }
    lastForwardValid_ = true;
    return RunSample{lastState_, lastForward_, lastDissipated_};
  }
}

// Defined before the generic lambdas of stoppedBy and warnings use it: clang 14 (the sanitizer
// build's compiler) leaves it uninstantiated otherwise.
template <Formulation F, int N>
RunEvent CoinRun::eventOf(const integrate::EventHit<N>& hit, const physics::CoinState& continuation) const {
  return {.event = static_cast<physics::ModelEvent>(hit.id),
          .t = hit.t,
          .state = seedState<F, N>(hit.y, continuation),
          .forward = forwardOf<F, N>(model_, hit.y),
          .dissipated = dissipatedOf<F, N>(hit.y)};
}

std::optional<RunEvent> CoinRun::stoppedBy() const {
  return std::visit(
      [this](const auto& run) -> std::optional<RunEvent> {
        if constexpr (kHybrid<decltype(run)>) {
          return run.stoppedBy(lastState_);
        } else {
          using Traits = RunTraits<std::decay_t<decltype(run)>>;
          const auto& hit = run.stoppedBy();
          // A fixed step may end past the duration and find an event there: not this run's.
          if (!hit || hit->t > duration_) return std::nullopt;
          // The hit lies within one unwrap interval of the last sample, so lastState_ continues it.
          return eventOf<Traits::kFormulation, Traits::kSize>(*hit, lastState_);
        }
      },
      trajectory_);
}

std::vector<RunEvent> CoinRun::warnings() const {
  return std::visit(
      [this](const auto& run) {
        if constexpr (kHybrid<decltype(run)>) {
          return run.warnings();
        } else {
          using Traits = RunTraits<std::decay_t<decltype(run)>>;
          std::vector<RunEvent> hits;
          for (const auto& hit : run.nonTerminalHits()) {
            if (hit.t > duration_) break;
            hits.push_back(eventOf<Traits::kFormulation, Traits::kSize>(hit, physics::CoinState{}));
          }
          return hits;
        }
      },
      trajectory_);
}

std::vector<ModeSwitch> CoinRun::switches() const {
  if (const auto* hybrid = std::get_if<HybridRun>(&trajectory_)) return hybrid->switches();
  return {};
}

integrate::Stats CoinRun::stats() const {
  return std::visit([](const auto& trajectory) { return trajectory.stats(); }, trajectory_);
}

}  // namespace coinroll::pipeline
