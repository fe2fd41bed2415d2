// The physics core integrated in time, checked against truths computed another way: conserved
// energy, Chaplygin's theta-parametrised equations, analytic steady states and K.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "integrate/trajectory.h"
#include "physics/dynamics.h"
#include "physics/observables.h"
#include "physics/steady.h"
#include "physics/coin_rhs.h"
#include "reference_solver.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;
using integrate::Method;
using integrate::SolverConfig;

using reference::kDeg;
using reference::kTight;

// A tilted coin rolling, precessing and wobbling (not a steady state).
CoinState wobblingState() { return {.theta = 20 * kDeg, .omega_X = 0.5, .omega_Y = 3.0, .omega_Z = 14.0}; }

TEST(EnergyConservation, DriftBelow1e10Over100NaturalPeriods) {
  for (const CoinModel& m : {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.02, 9.81)}) {
    integrate::Trajectory trajectory(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(wobblingState()), kTight);
    const double E0 = energy(m, wobblingState());
    double worst = 0;
    const double period = 2 * std::numbers::pi * naturalTime(m);
    for (int k = 1; k <= 1000; ++k) {
      const auto y = trajectory.stateAt(0.1 * k * period);
      ASSERT_TRUE(y.has_value());
      worst = std::max(worst, std::abs(energy(m, toState(*y)) - E0) / E0);
    }
    EXPECT_TRUE(isBelow(worst, 1e-10));
  }
}

TEST(ChaplyginIntegrals, ThetaParametrisedRatesMatchTheTimeIntegration) {
  // docs/derivations.md (4.1): while theta(t) increases, omega_Y and omega_Z as functions of
  // theta follow a linear ODE in theta alone. Integrate it separately and compare.
  const CoinModel m = ringModel(0.4, 0.0375, 0.015, 9.81);
  const CoinState start{.theta = 10 * kDeg, .omega_X = 2.0, .omega_Y = 1.0, .omega_Z = 4.0};
  const double Ma2 = m.M * m.a * m.a;
  auto inTheta = [&](double theta, const integrate::Vec<2>& w) {
    return integrate::Vec<2>(std::tan(theta) * w[0] + (m.I_Z / m.I_X) * w[1], Ma2 / (m.I_Z + Ma2) * w[0]);
  };
  integrate::Trajectory inTime(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(start), kTight);
  integrate::Trajectory alongTheta(inTheta, start.theta, integrate::Vec<2>(start.omega_Y, start.omega_Z), kTight);
  int compared = 0;
  for (double t = 0.001; t < 1.0; t += 0.001) {
    const CoinState s = toState(*inTime.stateAt(t));
    if (s.omega_X <= 0.05) break;  // theta stops increasing: the parametrisation ends
    const integrate::Vec<2> w = *alongTheta.stateAt(s.theta);
    EXPECT_TRUE(isNear(w[0], s.omega_Y, 1e-9));
    EXPECT_TRUE(isNear(w[1], s.omega_Z, 1e-9));
    ++compared;
  }
  EXPECT_GT(compared, 20);
}

double maxDeviationFromSteady(const CoinModel& m, const CoinState& steady, double duration) {
  integrate::Trajectory trajectory(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(steady), kTight);
  double worst = 0;
  for (double t = 0.01; t <= duration + 1e-12; t += 0.01) {
    const CoinState s = toState(*trajectory.stateAt(t));
    worst = std::max({worst, std::abs(s.theta - steady.theta), std::abs(s.omega_X) / naturalRate(m),
                      std::abs(s.omega_Y - steady.omega_Y) / naturalRate(m),
                      std::abs(s.omega_Z - steady.omega_Z) / naturalRate(m)});
  }
  return worst;
}

TEST(SteadyStates, StaySteadyForTenSeconds) {
  for (const CoinModel& m : {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.0375, 9.81)}) {
    const double rate = naturalRate(m);
    EXPECT_TRUE(isBelow(maxDeviationFromSteady(m, steadyCircle(m, 20 * kDeg, 1.5 * rate, +1), 10), 1e-9));
    EXPECT_TRUE(isBelow(maxDeviationFromSteady(m, steadyCircle(m, 30 * kDeg, 1.0 * rate, -1), 10), 1e-9));
    EXPECT_TRUE(isBelow(maxDeviationFromSteady(m, spinInPlace(m, 40 * kDeg), 10), 1e-9));
    EXPECT_TRUE(isBelow(maxDeviationFromSteady(m, straightRolling(2 * rate), 10), 1e-9));
  }
}

double largestTilt(const CoinModel& m, double omega_Z, double duration) {
  CoinState s = straightRolling(omega_Z);
  s.theta = 1e-4;
  integrate::Trajectory trajectory(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(s), kTight);
  double largest = 0;
  for (double t = 0.005; t <= duration; t += 0.005) {
    const auto y = trajectory.stateAt(t);
    if (!y) break;
    largest = std::max(largest, std::abs((*y)[kTheta]));
    if (largest > 0.1) break;
  }
  return largest;
}

TEST(StraightRolling, CriticalSpinSeparatesGrowthFromBoundedWobble) {
  for (const CoinModel& m : {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.0375, 9.81)}) {
    const double omega_c = criticalSpin(m), T = 40 * naturalTime(m);
    EXPECT_LT(largestTilt(m, 1.2 * omega_c, T), 1e-3);  // bounded: stays within 10x the kick
    EXPECT_GT(largestTilt(m, 0.8 * omega_c, T), 1e-2);  // unstable: grows 100x and more
  }
}

TEST(WobbleFrequency, SimulatedPeriodMatchesTwoPiOverRootK) {
  for (const CoinModel& m : {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.02, 9.81)}) {
    for (auto [thetaDeg, spin, branch] :
         {std::tuple{20.0, 1.0, +1}, std::tuple{45.0, 0.5, +1}, std::tuple{30.0, 0.8, -1}}) {
      CoinState s = steadyCircle(m, thetaDeg * kDeg, spin * naturalRate(m), branch);
      const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
      ASSERT_GT(K, 0);
      s.theta += 1e-5;  // small kick in tilt
      // Tilt maxima: omega_X = theta-dot falls through zero.
      std::vector<integrate::Event<kStateSize>> maxima{{.name = "max",
                                                        .g = [](double, const StateVec& y) { return y[kOmega_X]; },
                                                        .direction = -1,
                                                        .terminal = false}};
      integrate::Trajectory trajectory(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(s), kTight, maxima);
      const double expectedPeriod = 2 * std::numbers::pi / std::sqrt(K);
      trajectory.stateAt(10.5 * expectedPeriod);
      const auto& hits = trajectory.nonTerminalHits();
      ASSERT_GE(hits.size(), 10u);
      const double measured = (hits.back().t - hits.front().t) / static_cast<double>(hits.size() - 1);
      EXPECT_TRUE(isNear(measured / expectedPeriod, 1.0, 0.005)) << "theta " << thetaDeg << " branch " << branch;
    }
  }
}

TEST(Rk4OnTheCoin, ConvergesAtOrderFour) {
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  integrate::Trajectory reference(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(wobblingState()), kTight);
  const StateVec exact = *reference.stateAt(0.5);
  auto errorWith = [&](double dt) {
    integrate::Trajectory rk4(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(wobblingState()),
                              SolverConfig{.method = Method::Rk4, .dt = dt});
    return (*rk4.stateAt(0.5) - exact).norm();
  };
  EXPECT_TRUE(isNear(std::log2(errorWith(1e-3) / errorWith(5e-4)), 4, 0.2));
}

TEST(Dop853OnTheCoin, ErrorFallsWithTheTolerance) {
  // The adaptive method's "order": tightening rtol 100x cuts the error by 20x or more.
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  integrate::Trajectory reference(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(wobblingState()),
                                  SolverConfig{.rtol = 1e-13, .atol = 1e-15});
  const StateVec exact = *reference.stateAt(2.0);
  auto errorWith = [&](double rtol) {
    integrate::Trajectory run(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(wobblingState()),
                              SolverConfig{.rtol = rtol, .atol = rtol * 1e-2});
    return (*run.stateAt(2.0) - exact).norm();
  };
  EXPECT_GT(errorWith(1e-7) / errorWith(1e-9), 20);
}

}  // namespace
}  // namespace coinroll::physics
