#include "physics/steady.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "physics/dynamics.h"
#include "physics/observables.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;

constexpr double kDeg = std::numbers::pi / 180;

std::vector<CoinModel> coins() {
  return {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.03, 9.81), ringModel(0.4, 0.0375, 0.0375, 9.81),
          {.M = 0.01, .a = 0.012, .g = 9.81, .I_X = 5e-7, .I_Z = 8e-7, .effects = {}}};
}

// max |d(omega)/dt| and |d(theta)/dt|, relative to the size of the terms that cancel in eq. (14)
// (gravity g/a and the products omega_i omega_j, which reach (1/tan theta)^2 on the f- branch):
// zero up to round-off on a steady state.
double steadyDrift(const CoinModel& m, const CoinState& s) {
  const StateVec dy = rhs(m, 0, toVector(s));
  const double rate = std::max({naturalRate(m), std::abs(s.omega_Y), std::abs(s.omega_Z)});
  return std::max({std::abs(dy[kTheta]) / rate, std::abs(dy[kOmega_X]) / (rate * rate),
                   std::abs(dy[kOmega_Y]) / (rate * rate), std::abs(dy[kOmega_Z]) / (rate * rate)});
}

TEST(SteadyStates, CirclesOfBothBranchesHaveNoAngularAcceleration) {
  for (const CoinModel& m : coins()) {
    for (double thetaDeg : {1.0, 10.0, 30.0, 60.0, 85.0}) {
      for (double spin : {0.3, 2.0, 8.0}) {
        for (int branch : {+1, -1}) {
          const CoinState s = steadyCircle(m, thetaDeg * kDeg, spin * naturalRate(m), branch);
          EXPECT_TRUE(isBelow(steadyDrift(m, s), 1e-12)) << "theta " << thetaDeg << " spin " << spin << " branch " << branch;
        }
      }
    }
  }
}

TEST(SteadyStates, SpinInPlaceKeepsTheCentreOfMassAtRest) {
  for (const CoinModel& m : coins()) {
    for (double thetaDeg : {5.0, 30.0, 70.0}) {
      const CoinState s = spinInPlace(m, thetaDeg * kDeg);
      EXPECT_TRUE(isBelow(steadyDrift(m, s), 1e-12));
      EXPECT_TRUE(isBelow(centreOfMassVelocity(m, s).norm(), 1e-15));
      // Steady state 2 of the seed: the floor pushes straight up with the weight, F = 0 (ERRATA).
      const Reaction r = reaction(m, s);
      EXPECT_TRUE(isNear(r.N, m.M * m.g, 1e-12 * m.M * m.g));
      EXPECT_TRUE(isBelow(r.F, 1e-12 * m.M * m.g));
      // The contact point circles at radius a sin(theta) (seed: R_C = sin(theta0) in units of a).
      EXPECT_TRUE(isNear(circleRadii(m, s).contact, m.a * std::sin(thetaDeg * kDeg), 1e-15));
    }
  }
}

TEST(SteadyStates, DiskMatchesTheSeedsDimensionlessFormulas) {
  const CoinModel unit = diskModel(1, 1, 1);
  for (double theta : {0.1, 0.5, 1.2}) {
    for (double omega_Z : {0.5, 3.0}) {
      const double root = std::sqrt(9 * omega_Z * omega_Z + 4 * std::sin(theta) * std::sin(theta) / std::cos(theta));
      EXPECT_TRUE(isNear(steadyCircle(unit, theta, omega_Z, +1).omega_Y, (-3 * omega_Z + root) / std::tan(theta), 1e-12));
      EXPECT_TRUE(isNear(steadyCircle(unit, theta, omega_Z, -1).omega_Y, (-3 * omega_Z - root) / std::tan(theta), 1e-11));
    }
    EXPECT_TRUE(isNear(spinInPlace(unit, theta).omega_Y, 2 * std::sqrt(std::cos(theta)), 1e-15));
  }
  EXPECT_TRUE(isNear(criticalSpin(unit), 1 / std::sqrt(3.0), 1e-15));
}

TEST(SteadyStates, CircleWithoutSpinIsSpinningInPlace) {
  // omega_Z = 0 leaves I_X tan(theta) omega_Y^2 = M g a sin(theta): omega_Y = +-sqrt(M g a cos(theta) / I_X),
  // the "+ sqrt" root f+ being spin-in-place's (seed steady state 2) for theta > 0 and f- its mirror.
  for (const CoinModel& m : coins()) {
    for (double thetaDeg : {1.0, 30.0, 80.0}) {
      const double expected = std::sqrt(m.M * m.g * m.a * std::cos(thetaDeg * kDeg) / m.I_X);
      EXPECT_TRUE(isNear(steadyCircle(m, thetaDeg * kDeg, 0.0, +1).omega_Y, expected, 1e-13 * expected)) << thetaDeg;
      EXPECT_TRUE(isNear(steadyCircle(m, thetaDeg * kDeg, 0.0, -1).omega_Y, -expected, 1e-13 * expected)) << thetaDeg;
      EXPECT_TRUE(isNear(steadyCircle(m, thetaDeg * kDeg, 0.0, +1).omega_Y, spinInPlace(m, thetaDeg * kDeg).omega_Y,
                         1e-13 * expected));
    }
  }
}

TEST(SteadyStates, TiltsOfNinetyDegreesAndBeyondAreRefused) {
  // The contract of steady.h: |theta| >= pi/2 throws, pi/2 itself included (flat: tan and
  // 1 / cos theta blow up).
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  for (const double theta : {std::numbers::pi / 2, -std::numbers::pi / 2, 1.6, -2.0}) {
    EXPECT_THROW(steadyCircle(m, theta, 10.0, +1), std::invalid_argument) << theta;
    EXPECT_THROW(steadyCircle(m, theta, 10.0, -1), std::invalid_argument) << theta;
    EXPECT_THROW(spinInPlace(m, theta), std::invalid_argument) << theta;
  }
  EXPECT_NO_THROW(steadyCircle(m, std::nextafter(std::numbers::pi / 2, 0.0), 10.0, +1));
}

TEST(SteadyStates, BranchesSwapUnderReversedSpin) {
  // f+(omega_Z, theta) = -f-(-omega_Z, theta) (seed section 5).
  const CoinModel m = ringModel(0.4, 0.0375, 0.02, 9.81);
  for (double omega_Z : {-20.0, 3.0, 40.0}) {
    EXPECT_TRUE(isNear(steadyCircle(m, 0.3, omega_Z, +1).omega_Y, -steadyCircle(m, 0.3, -omega_Z, -1).omega_Y, 1e-12));
  }
}

TEST(SteadyStates, SmallTiltPlusBranchIsTheSeedsLargeCircle) {
  // Steady state 4: omega_Y ~ (2/3) sin(theta0) / omega_Z0 for the unit disk and theta0 << 1.
  const CoinModel unit = diskModel(1, 1, 1);
  const double theta = 1e-6, omega_Z = 2.0;
  EXPECT_TRUE(isNear(steadyCircle(unit, theta, omega_Z, +1).omega_Y, 2.0 / 3.0 * std::sin(theta) / omega_Z, 1e-17));
}

// 4x4 Jacobian of (theta, omega_X, omega_Y, omega_Z)-dot by central differences of rhs().
Eigen::Matrix4d tiltJacobian(const CoinModel& m, const CoinState& s) {
  const int indices[4] = {kTheta, kOmega_X, kOmega_Y, kOmega_Z};
  Eigen::Matrix4d J;
  const StateVec y0 = toVector(s);
  for (int col = 0; col < 4; ++col) {
    const double h = 1e-6 * std::max(1.0, std::abs(y0[indices[col]]));
    StateVec plus = y0, minus = y0;
    plus[indices[col]] += h;
    minus[indices[col]] -= h;
    const StateVec df = (rhs(m, 0, plus) - rhs(m, 0, minus)) / (2 * h);
    for (int row = 0; row < 4; ++row) J(row, col) = df[indices[row]];
  }
  return J;
}

TEST(WobbleStiffness, MatchesTheEigenvaluesOfTheNumericalJacobian) {
  for (const CoinModel& m : coins()) {
    for (double thetaDeg : {0.0, 5.0, 20.0, 45.0, 75.0}) {
      for (double spin : {0.2, 1.0, 4.0}) {
        for (int branch : {+1, -1}) {
          if (thetaDeg == 0 && branch == -1) continue;
          const CoinState s = steadyCircle(m, thetaDeg * kDeg, spin * naturalRate(m), branch);
          const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
          // The Jacobian has eigenvalues 0, 0 (the family of neighbouring steady states) and
          // lambda^2 = -K; the largest |lambda^2| is the wobble's.
          const Eigen::Vector4cd eigenvalues = tiltJacobian(m, s).eigenvalues();
          std::complex<double> dominant = 0;
          for (const auto& lambda : eigenvalues) {
            if (std::abs(lambda) > std::abs(dominant)) dominant = lambda;
          }
          const double lambdaSquared = (dominant * dominant).real();
          EXPECT_TRUE(isNear(-lambdaSquared / K, 1.0, 1e-6))
              << "theta " << thetaDeg << " spin " << spin << " branch " << branch << " K " << K;
        }
      }
    }
  }
}

TEST(WobbleStiffness, StraightRollingReproducesTheSeedsEigenvalues) {
  // Seed 5.1: lambda^2 = (4/5)(1 - 3 omega_Z0^2) for the unit disk.
  const CoinModel unit = diskModel(1, 1, 1);
  for (double omega_Z : {0.1, 0.5, 1 / std::sqrt(3.0), 2.0}) {
    EXPECT_TRUE(isNear(-wobbleStiffness(unit, 0, 0, omega_Z), 0.8 * (1 - 3 * omega_Z * omega_Z), 1e-15));
  }
}

TEST(WobbleStiffness, ChangesSignAtTheCriticalSpin) {
  for (const CoinModel& m : coins()) {
    const double omega_c = criticalSpin(m);
    EXPECT_LT(wobbleStiffness(m, 0, 0, 0.999 * omega_c), 0);
    EXPECT_GT(wobbleStiffness(m, 0, 0, 1.001 * omega_c), 0);
  }
}

TEST(WobbleStiffness, SpinInPlaceIsAlwaysStable) {
  // docs/derivations.md eq. (3.8): K = [M a^2 omega_Y0^2 + 3 M g a sin^2/cos] / (I_X + M a^2) > 0.
  for (const CoinModel& m : coins()) {
    for (double thetaDeg : {2.0, 30.0, 80.0}) {
      const CoinState s = spinInPlace(m, thetaDeg * kDeg);
      const double Ma2 = m.M * m.a * m.a, th = s.theta;
      const double expected = (Ma2 * s.omega_Y * s.omega_Y + 3 * m.M * m.g * m.a * std::sin(th) * std::tan(th)) / (m.I_X + Ma2);
      const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
      EXPECT_GT(K, 0);
      EXPECT_TRUE(isNear(K / expected, 1.0, 1e-12));
    }
  }
}

}  // namespace
}  // namespace coinroll::physics
