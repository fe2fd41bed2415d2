#pragma once
// A spin-down integrated directly on the physics (no pipeline), in either formulation, with the
// dissipated energy as the extra state and a coin-flat stop at a tilt the test chooses.

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "integrate/trajectory.h"
#include "physics/coin_rhs.h"
#include "physics/dynamics.h"
#include "physics/observables.h"
#include "physics/quaternion_dynamics.h"

namespace coinroll::physics {

struct SpinDownSample {
  double t = 0;  // s
  CoinState state;
  double dissipated = 0;  // J, integrated from the declared power
};

struct SpinDown {
  std::vector<SpinDownSample> samples;  // at the requested times, then the stop
  std::optional<double> flatAt;         // s, time of the coin-flat stop
};

inline double tiltAboveFloor(const CoinState& s) { return std::numbers::pi / 2 - std::abs(s.theta); }

// Runs `model` from `start` until the tilt above the floor falls to `endAlpha` (rad), sampling at
// the increasing `times` (s) that come before the stop.
template <Formulation F>
SpinDown runSpinDown(const CoinModel& model, const CoinState& start, double endAlpha, const std::vector<double>& times,
                     const integrate::SolverConfig& solver = {}) {
  constexpr int kMotion = kMotionSize<F>, N = kMotion + 1;
  using Y = integrate::Vec<N>;
  const auto seed = [](const Y& y, const CoinState& continuation) {
    if constexpr (F == Formulation::EulerAngles)
      return toState(y.template head<kMotion>());
    else
      return toEulerState(toQuaternionState(y.template head<kMotion>()), continuation);
  };
  Y y0;
  if constexpr (F == Formulation::EulerAngles)
    y0.template head<kMotion>() = toVector(start);
  else
    y0.template head<kMotion>() = toVector(fromEulerState(start));
  y0[N - 1] = 0;
  std::vector<integrate::Event<N>> flat{
      {.name = "coin-flat",
       .g = [endAlpha, seed](double, const Y& y) { return tiltAboveFloor(seed(y, CoinState{})) - endAlpha; },
       .direction = -1}};
  integrate::Trajectory run(CoinRhs<F>{model}, 0.0, y0, solver, flat);
  SpinDown result;
  CoinState continuation = start;
  // Samples may be far apart: phi and psi are then not unwrapped, which alpha, Omega and the
  // energy, all these tests read, do not need.
  for (const double t : times) {
    const std::optional<Y> y = run.stateAt(t);
    if (!y) break;
    continuation = seed(*y, continuation);
    result.samples.push_back({t, continuation, (*y)[N - 1]});
  }
  if (run.stoppedBy()) {
    result.flatAt = run.stoppedBy()->t;
    result.samples.push_back({run.stoppedBy()->t, seed(run.stoppedBy()->y, continuation), run.stoppedBy()->y[N - 1]});
  }
  return result;
}

}  // namespace coinroll::physics

namespace coinroll::physics {

// n times spaced evenly in log(tEnd - t) from tEnd - longest to tEnd - shortest, increasing.
inline std::vector<double> timesBefore(double tEnd, double longest, double shortest, int n) {
  std::vector<double> times;
  for (int i = 0; i < n; ++i) {
    times.push_back(tEnd - longest * std::pow(shortest / longest, static_cast<double>(i) / (n - 1)));
  }
  return times;
}

// n times evenly spaced over [0, duration].
inline std::vector<double> evenTimes(double duration, int n) {
  std::vector<double> times;
  for (int i = 0; i < n; ++i) times.push_back(duration * i / (n - 1));
  return times;
}

}  // namespace coinroll::physics
