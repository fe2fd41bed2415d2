// Where the explicit fixed-step methods fail on the coin, measured: the largest step that keeps
// the energy bounded as the spin grows, against RK4's linear-stability limit, and the energy
// error over 10^4 wobble periods for each method. Writes two CSV files that
// tools/plot_work_precision.py charts and tests/physics/stability_test.cpp quotes.
//
// Run: build/bench/stability [OUT_DIR]   (default docs/data/; writes stability_steps.csv,
// stability_energy.csv)

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "integrate/trajectory.h"
#include "physics/coin_rhs.h"
#include "physics/dynamics.h"
#include "physics/observables.h"
#include "physics/steady.h"

namespace {

using namespace coinroll;
using integrate::Method;
using integrate::SolverConfig;
using physics::CoinModel;
using physics::CoinState;
using physics::StateVec;

using CoinRhs = physics::CoinRhs<physics::Formulation::EulerAngles>;

const CoinModel kDisk = physics::diskModel(0.4, 0.0375, 9.81);
constexpr double kTilt = 20 * std::numbers::pi / 180;  // rad, tilt of the steady circles
constexpr double kKick = 1e-3;                         // rad, tilt added so the wobble mode is excited
// "Stable" for the step search: the relative energy error stays below this over kPeriods.
constexpr double kEnergyBound = 1e-2;
constexpr double kPeriods = 100;

// The f+ steady circle at spin `spin` (natural units) with its tilt kicked.
CoinState kickedCircle(double spin) {
  CoinState s = physics::steadyCircle(kDisk, kTilt, spin * physics::naturalRate(kDisk), +1);
  s.theta += kKick;
  return s;
}

double wobbleRate(double spin) {
  const CoinState s = physics::steadyCircle(kDisk, kTilt, spin * physics::naturalRate(kDisk), +1);
  return std::sqrt(physics::wobbleStiffness(kDisk, s.theta, s.omega_Y, s.omega_Z));  // rad/s
}

// Largest relative energy error over `duration`, sampled on every step; infinity once the run
// throws (non-finite state) or leaves the bound by a factor 10^6 (no need to follow a blow-up).
double maxEnergyError(Method method, double dt, const CoinState& start, double duration) {
  const double E0 = physics::energy(kDisk, start);
  integrate::Trajectory trajectory(CoinRhs{kDisk}, 0.0, physics::toVector(start),
                                   SolverConfig{.method = method, .dt = dt});
  double worst = 0;
  try {
    for (long k = 1; k * dt <= duration; ++k) {
      const auto y = trajectory.stateAt(k * dt);
      worst = std::max(worst, std::abs(physics::energy(kDisk, physics::toState(*y)) - E0) / E0);
      if (!(worst < 1e6 * kEnergyBound)) return std::numeric_limits<double>::infinity();
    }
  } catch (const std::runtime_error&) {
    return std::numeric_limits<double>::infinity();
  }
  return worst;
}

// Bisection in log(dt) for the boundary between bounded and unbounded energy error.
double largestStableStep(Method method, double spin) {
  const double period = 2 * std::numbers::pi / wobbleRate(spin);
  double stable = 1e-7, unstable = period;
  for (int i = 0; i < 30 && unstable / stable > 1.001; ++i) {
    const double dt = std::sqrt(stable * unstable);
    (maxEnergyError(method, dt, kickedCircle(spin), kPeriods * period) < kEnergyBound ? stable : unstable) = dt;
  }
  return stable;
}

void writeStepLimits(const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "spin_natural,wobble_rate,method,largest_stable_dt,rk4_linear_limit\n";
  fmt::print("{:>6} {:>10} {:>12} {:>12} {:>12} {:>8}\n", "spin", "sqrt(K)", "euler dt", "rk4 dt", "2.83/sqrtK",
             "ratio");
  for (double spin : {1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0, 30.0}) {
    const double rate = wobbleRate(spin);
    // RK4's stability region meets the imaginary axis at |h lambda| = 2 sqrt 2; the wobble is
    // the linearisation's only oscillatory mode (eigenvalues +-i sqrt K, docs/derivations.md §3).
    const double rk4Linear = 2 * std::numbers::sqrt2 / rate;
    const double euler = largestStableStep(Method::Euler, spin), rk4 = largestStableStep(Method::Rk4, spin);
    out << fmt::format("{},{:.17g},euler,{:.6g},{:.6g}\n{},{:.17g},rk4,{:.6g},{:.6g}\n", spin, rate, euler, rk4Linear,
                       spin, rate, rk4, rk4Linear);
    fmt::print("{:6.1f} {:10.4g} {:12.4g} {:12.4g} {:12.4g} {:8.4f}\n", spin, rate, euler, rk4, rk4Linear,
               rk4 / rk4Linear);
  }
}

// Energy error against time over 10^4 wobble periods at spin 1.5, sampled at log-spaced times.
void writeEnergyHistory(const std::filesystem::path& path) {
  constexpr double kSpin = 1.5;
  const double period = 2 * std::numbers::pi / wobbleRate(kSpin), end = 1e4 * period;
  const double rk4Limit = 2 * std::numbers::sqrt2 / wobbleRate(kSpin);
  struct Run {
    std::string label;
    SolverConfig config;
  };
  const Run runs[] = {
      {fmt::format("euler dt={:.2g}", rk4Limit / 1000), {.method = Method::Euler, .dt = rk4Limit / 1000}},
      {fmt::format("rk4 dt={:.2g}", rk4Limit / 4), {.method = Method::Rk4, .dt = rk4Limit / 4}},
      {fmt::format("gauss4 dt={:.2g}", rk4Limit / 4), {.method = Method::Gauss4, .dt = rk4Limit / 4}},
      {"dop853 rtol=1e-10 (default)", {.method = Method::Dop853, .rtol = 1e-10, .atol = 1e-12}},
  };
  std::ofstream out(path);
  out << "method,periods,energy_error\n";
  const CoinState start = kickedCircle(kSpin);
  const double E0 = physics::energy(kDisk, start);
  for (const Run& run : runs) {
    integrate::Trajectory trajectory(CoinRhs{kDisk}, 0.0, physics::toVector(start), run.config);
    double error = 0;
    try {
      for (double periods = 1; periods <= 1e4 * (1 + 1e-12) && error < 1; periods *= std::pow(10.0, 0.05)) {
        // Fixed-step runs are sampled on step points: their cubic interpolant conserves nothing.
        double t = std::min(periods * period, end);
        if (!integrate::isAdaptive(run.config.method)) t = run.config.dt * std::round(t / run.config.dt);
        const auto y = trajectory.stateAt(t);
        error = std::abs(physics::energy(kDisk, physics::toState(*y)) - E0) / E0;
        out << fmt::format("{},{:.6g},{:.6g}\n", run.label, periods, error);
      }
    } catch (const std::runtime_error&) {
      error = std::numeric_limits<double>::infinity();  // the blow-up ends the line
    }
    fmt::print("{:30} energy error after {} periods: {:.3g}  ({} rhs evaluations)\n", run.label,
               error < 1 ? "1e4" : "<1e4", error, trajectory.stats().rhsEvaluations);
  }
}

// The target: the default solver (DOP853, rtol 1e-10, atol 1e-12) on a tilted coin
// rolling, precessing and wobbling, 200 s; largest relative energy error on a 0.01 s grid.
void printDefaultSolverDrift() {
  const CoinState start{.theta = 20 * std::numbers::pi / 180, .omega_X = 0.5, .omega_Y = 3.0, .omega_Z = 14.0};
  const double E0 = physics::energy(kDisk, start);
  integrate::Trajectory trajectory(CoinRhs{kDisk}, 0.0, physics::toVector(start), SolverConfig{});
  double worst = 0;
  for (int k = 1; k <= 20'000; ++k) {
    const auto y = trajectory.stateAt(0.01 * k);
    worst = std::max(worst, std::abs(physics::energy(kDisk, physics::toState(*y)) - E0) / E0);
  }
  fmt::print("default solver, 200 s of a wobbling coin: max relative energy error {:.3g} ({} steps)\n", worst,
             trajectory.stats().acceptedSteps);
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path outDir = argc > 1 ? argv[1] : "docs/data";
  fmt::print("Largest step keeping |dE/E| < {} over {} wobble periods, f+ circle at 20 deg + {} rad kick\n",
             kEnergyBound, kPeriods, kKick);
  writeStepLimits(outDir / "stability_steps.csv");
  writeEnergyHistory(outDir / "stability_energy.csv");
  printDefaultSolverDrift();
}
