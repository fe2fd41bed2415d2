// The geometric method's claims, each against a truth we did not compute with it: exact
// conservation of quadratic invariants, bounded (not drifting) energy on a Hamiltonian system,
// and the cost accounting of its Newton iteration.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "integrate/trajectory.h"
#include "tolerance.h"

namespace coinroll::integrate {
namespace {

using coinroll::testing::isBelow;
using V2 = Vec<2>;
using V4 = Vec<4>;

struct Oscillator {
  V2 operator()(double, const V2& y) const { return V2(y[1], -y[0]); }
};

TEST(Gauss4, ConservesTheOscillatorsQuadraticInvariantToRoundOff) {
  // Gauss collocation conserves every quadratic invariant exactly (Cooper 1987; GNI IV.2.1):
  // what is left is round-off, growing like a random walk.
  Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = Method::Gauss4, .dt = 0.1});
  double worst = 0;
  for (int k = 1; k <= 1000; ++k) {
    const V2 y = *trajectory.stateAt(2.0 * k);  // 2000 time units, 320 periods, 2 10^4 steps
    worst = std::max(worst, std::abs(y.squaredNorm() - 1));
  }
  EXPECT_TRUE(isBelow(worst, 1e-12));  // measured 1.8e-14
}

// Kepler's problem q'' = -q / |q|^3 as y = (q, p), started at perihelion with eccentricity 0.5.
struct Kepler {
  V4 operator()(double, const V4& y) const {
    const double r3 = std::pow(y.head<2>().squaredNorm(), 1.5);
    return V4(y[2], y[3], -y[0] / r3, -y[1] / r3);
  }
  static constexpr double kEccentricity = 0.5;
  static V4 start() { return V4(1 - kEccentricity, 0, 0, std::sqrt((1 + kEccentricity) / (1 - kEccentricity))); }
  static double energy(const V4& y) { return 0.5 * y.tail<2>().squaredNorm() - 1 / y.head<2>().norm(); }
  static double angularMomentum(const V4& y) { return y[0] * y[3] - y[1] * y[2]; }
};

struct KeplerErrors {
  double energyFirstOrbits = 0, energyLastOrbits = 0, angularMomentum = 0;
};

// Largest energy error over the first and the last 50 of `orbits` orbits (period 2 pi), and the
// largest angular-momentum error overall. Sampled on step points: the interpolant between them
// is only order 3 and conserves nothing.
KeplerErrors keplerErrors(Method method, double dt, int orbits) {
  Trajectory trajectory(Kepler{}, 0.0, Kepler::start(), SolverConfig{.method = method, .dt = dt});
  const double E0 = Kepler::energy(Kepler::start()), L0 = Kepler::angularMomentum(Kepler::start());
  const double window = 50 * 2 * std::numbers::pi, end = orbits * 2 * std::numbers::pi;
  KeplerErrors errors;
  constexpr int kStepsPerSample = 5;
  for (long k = 1; k * kStepsPerSample * dt <= end; ++k) {
    const double t = k * kStepsPerSample * dt;
    const V4 y = *trajectory.stateAt(t);
    const double energyError = std::abs(Kepler::energy(y) - E0);
    if (t <= window) errors.energyFirstOrbits = std::max(errors.energyFirstOrbits, energyError);
    if (t > end - window) errors.energyLastOrbits = std::max(errors.energyLastOrbits, energyError);
    errors.angularMomentum = std::max(errors.angularMomentum, std::abs(Kepler::angularMomentum(y) - L0));
  }
  return errors;
}

constexpr int kKeplerOrbits = 400;
constexpr double kKeplerStep = 0.1;  // 63 steps per orbit

TEST(Gauss4, KeplerEnergyErrorStaysBoundedOverFourHundredOrbits) {
  const KeplerErrors gauss = keplerErrors(Method::Gauss4, kKeplerStep, kKeplerOrbits);
  // Symplectic: the error oscillates with the orbit but does not grow (GNI IX.8); 1.2 allows the
  // last window to catch a slightly higher peak of the same oscillation.
  EXPECT_TRUE(isBelow(gauss.energyLastOrbits, 1.2 * gauss.energyFirstOrbits));
  EXPECT_TRUE(isBelow(gauss.energyFirstOrbits, 3e-5));  // measured 1.5e-5: order 4 at 63 steps per orbit
  // Quadratic, so exact but for round-off and the 1e-15 Newton tolerance over 2.5e4 steps
  // (measured 1.3e-11, six orders of magnitude below the energy error).
  EXPECT_TRUE(isBelow(gauss.angularMomentum, 5e-11));
}

TEST(Gauss4, Rk4AtTheSameStepDriftsOnKepler) {
  // The contrast that makes the previous test meaningful: RK4, same order and step, not
  // symplectic, loses energy linearly in time: the last 50 of 400 orbits end 400 / 50 = 8 times
  // further off than the first 50 (measured 8.3).
  const KeplerErrors rk4 = keplerErrors(Method::Rk4, kKeplerStep, kKeplerOrbits);
  EXPECT_GT(rk4.energyLastOrbits, 5 * rk4.energyFirstOrbits);
}

TEST(Gauss4, CountsStageAndJacobianEvaluations) {
  // A linear problem: the finite-difference Jacobian is exact, Newton converges in one
  // correction and the second confirms it; the Jacobian is computed once for the whole run.
  Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = Method::Gauss4, .dt = 0.01});
  trajectory.stateAt(1.0);
  const Stats& stats = trajectory.stats();
  EXPECT_EQ(stats.acceptedSteps, 100);
  // 1 initial slope + 2 Jacobian columns + per step: 2 stages x iterations + 1 end slope.
  EXPECT_GE(stats.rhsEvaluations, 1 + 2 + 100 * (2 * 2 + 1));
  EXPECT_LE(stats.rhsEvaluations, 1 + 2 + 100 * (2 * 3 + 1));
}

}  // namespace
}  // namespace coinroll::integrate
