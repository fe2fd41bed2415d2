#include "pipeline/coin_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "physics/observables.h"
#include "pipeline/cancelled.h"
#include "pipeline/formulation_run.h"
#include "pipeline/hybrid_run.h"

namespace coinroll::pipeline {

namespace {

using physics::Formulation;

// rad. The quaternion carries no phi or psi: toEulerState recovers them modulo 2 pi and unwraps
// against the previous sample, which is right only while they turn by less than pi in between.
// Sampling the dense output every quarter turn keeps a factor 4 in hand for rates that grow
// within one such interval (they do near flat, like 1 / sqrt(cos theta)).
constexpr double kUnwrapTurn = std::numbers::pi / 4;

std::unique_ptr<Motion> startMotion(const Simulation& simulation) {
  if (simulation.sliding) return std::make_unique<HybridRun>(simulation);
  if (simulation.formulation == Formulation::EulerAngles)
    return startFormulationRun<Formulation::EulerAngles>(simulation);
  return startFormulationRun<Formulation::Quaternion>(simulation);
}

}  // namespace

CoinRun::CoinRun(const Simulation& simulation)
    : motion_(startMotion(simulation)),
      last_{.state = simulation.initial, .forward = {}, .dissipated = 0},
      cancel_(simulation.cancel) {}

std::optional<RunSample> CoinRun::sampleAt(double t) {
  throwIfCancelled(cancel_);
  if (!motion_->continuesAngles()) return motion_->sampleAt(t, last_.state);
  if (t < lastTime_) {
    throw std::logic_error(
        fmt::format("CoinRun::stateAt: queries must not go back in time ({} after {})", t, lastTime_));
  }
  while (!sampled_ || lastTime_ < t) {
    throwIfCancelled(cancel_);
    // In flight phi-dot and psi-dot are unbounded where the tumbling coin passes flat, which they
    // cannot be unwrapped through anyway; the body's own turn keeps the samples finite there.
    const double turnRate = last_.forward.flying ? last_.forward.omega.norm()
                                                 : std::max(std::abs(physics::precessionRate(last_.state)),
                                                            std::abs(physics::spinRate(last_.state)));
    const double next = turnRate > 0 ? std::min(t, lastTime_ + kUnwrapTurn / turnRate) : t;
    std::optional<RunSample> sample = motion_->sampleAt(next, last_.state);
    if (!sample) return std::nullopt;
    // The first sample, at the start, keeps the scene's initial state as given, not its round trip
    // through the quaternion.
    if (next > lastTime_) last_.state = sample->state;
    last_.forward = sample->forward;
    last_.dissipated = sample->dissipated;
    last_.impacts = sample->impacts;
    lastTime_ = next;
    sampled_ = true;
  }
  return last_;
}

std::optional<physics::CoinState> CoinRun::stateAt(double t) {
  const std::optional<RunSample> sample = sampleAt(t);
  if (!sample) return std::nullopt;
  return sample->state;
}

// The end lies within one unwrap interval of the last sample, so the last sample continues it.
std::optional<RunEvent> CoinRun::stoppedBy() const { return motion_->stoppedBy(last_.state); }

std::vector<RunEvent> CoinRun::warnings() const { return motion_->warnings(); }

std::vector<ModeSwitch> CoinRun::switches() const { return motion_->switches(); }

std::vector<ImpactRecord> CoinRun::impacts() const { return motion_->impacts(); }

integrate::Stats CoinRun::stats() const { return motion_->stats(); }

}  // namespace coinroll::pipeline
