#include "physics/steady.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/dynamics.h"
#include "physics/observables.h"
#include "reference_solver.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;

using reference::kDeg;

std::vector<CoinModel> coins() {
  return {diskModel(0.4, 0.0375, 9.81),
          ringModel(0.4, 0.0375, 0.03, 9.81),
          ringModel(0.4, 0.0375, 0.0375, 9.81),
          {.M = 0.01, .a = 0.012, .g = 9.81, .I_X = 5e-7, .I_Z = 8e-7, .rim = {}, .effects = {}}};
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
          EXPECT_TRUE(isBelow(steadyDrift(m, s), 1e-12))
              << "theta " << thetaDeg << " spin " << spin << " branch " << branch;
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
      // Steady state 2 of the seed: the floor pushes straight up with the weight, F = 0 (docs/seed.md §5).
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
      EXPECT_TRUE(
          isNear(steadyCircle(unit, theta, omega_Z, +1).omega_Y, (-3 * omega_Z + root) / std::tan(theta), 1e-12));
      EXPECT_TRUE(
          isNear(steadyCircle(unit, theta, omega_Z, -1).omega_Y, (-3 * omega_Z - root) / std::tan(theta), 1e-11));
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
      const double expected =
          (Ma2 * s.omega_Y * s.omega_Y + 3 * m.M * m.g * m.a * std::sin(th) * std::tan(th)) / (m.I_X + Ma2);
      const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
      EXPECT_GT(K, 0);
      EXPECT_TRUE(isNear(K / expected, 1.0, 1e-12));
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Coins with a rim (docs/rim.md §5): the toy's disk, a = 37.5 mm, h = 13 mm, with the solid cylinder's moments
// I_X = M (a^2/4 + h^2/12), I_Z = M a^2/2 as simple stand-ins, fully rounded (rho = h/2) and cornered (rho = 1.6 mm).

constexpr double kToyRadius = 0.0375, kToyThickness = 0.013;

CoinModel thickDisk(double edgeRadius, double thickness = kToyThickness) {
  const double M = 0.4, a = kToyRadius;
  return {.M = M,
          .a = a,
          .g = 9.81,
          .I_X = M * (a * a / 4 + thickness * thickness / 12),
          .I_Z = M * a * a / 2,
          .rim = {.thickness = thickness, .edgeRadius = edgeRadius},
          .effects = {}};
}

std::vector<CoinModel> thickCoins() { return {thickDisk(kToyThickness / 2), thickDisk(0.0016)}; }

bool hasCorners(const CoinModel& m) { return m.rim.edgeRadius < m.rim.thickness / 2; }

// Where a cornered rim's centre of mass stands straight above the contact: tan = (h/2 - rho) / (a - rho)
// (docs/rim.md eq. 1.7). Below it gravity rights the coin.
double balanceAngle(const CoinModel& m) {
  return std::atan((m.rim.thickness / 2 - m.rim.edgeRadius) / (m.a - m.rim.edgeRadius));
}

// The contact vector from the contract's definition, c = -(a - rho) e_Y + sign(theta) (h/2 - rho) e_Z - rho y_hat,
// in XYZ components, written here again so the checks below do not lean on src/physics.
Eigen::Vector3d referenceContact(const CoinModel& m, double theta) {
  const double rho = m.rim.edgeRadius, side = theta < 0 ? -1.0 : 1.0;
  const Eigen::Vector3d up(0, std::cos(theta), -std::sin(theta));
  return Eigen::Vector3d(0, -(m.a - rho), side * (m.rim.thickness / 2 - rho)) - rho * up;
}

// (theta, omega_X, omega_Y, omega_Z)-dot from docs/rim.md eq. 2.7 assembled with Eigen from the contract's vectors:
// [I + M (|c|^2 1 - c c^t)] omega' = -Omega x I omega + M c x (Omega x v - omega x c') + M g c x y_hat.
Eigen::Vector4d referenceTiltRates(const CoinModel& m, const Eigen::Vector4d& x) {
  const double theta = x[0];
  const Eigen::Vector3d omega = x.tail<3>();
  const double rho = m.rim.edgeRadius;
  const Eigen::Vector3d up(0, std::cos(theta), -std::sin(theta));
  const Eigen::Vector3d c = referenceContact(m, theta);
  const Eigen::Vector3d cRate = omega.x() * Eigen::Vector3d(0, rho * std::sin(theta), rho * std::cos(theta));
  const Eigen::Vector3d frameRate(omega.x(), omega.y(), -omega.y() * std::tan(theta));
  const Eigen::Matrix3d inertia = Eigen::Vector3d(m.I_X, m.I_X, m.I_Z).asDiagonal();
  const Eigen::Vector3d v = -omega.cross(c);
  const Eigen::Matrix3d mass = inertia + m.M * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  const Eigen::Vector3d f = -frameRate.cross(inertia * omega) + m.M * c.cross(frameRate.cross(v) - omega.cross(cRate)) +
                            m.M * m.g * c.cross(up);
  Eigen::Vector4d rates;
  rates << omega.x(), mass.partialPivLu().solve(f);
  return rates;
}

Eigen::Vector4d tiltVector(const CoinState& s) { return {s.theta, s.omega_X, s.omega_Y, s.omega_Z}; }

// As steadyDrift, for the reference equations.
double referenceDrift(const CoinModel& m, const CoinState& s) {
  const Eigen::Vector4d dx = referenceTiltRates(m, tiltVector(s));
  const double rate = std::max({naturalRate(m), std::abs(s.omega_Y), std::abs(s.omega_Z)});
  return std::max(std::abs(dx[0]) / rate, dx.tail<3>().cwiseAbs().maxCoeff() / (rate * rate));
}

// The size of the terms that cancel in docs/rim.md eq. 5.1, N m: gravity's and the rates' (M a^2 omega^2).
double residualScale(const CoinModel& m, const CoinState& s) {
  const double rate = std::max({naturalRate(m), std::abs(s.omega_Y), std::abs(s.omega_Z)});
  return m.M * m.a * m.a * rate * rate;
}

// 4x4 Jacobian by central differences of any (theta, omega)-rate function.
template <typename Rates>
Eigen::Matrix4d centralJacobian(const Rates& rates, const Eigen::Vector4d& x0) {
  Eigen::Matrix4d J;
  for (int col = 0; col < 4; ++col) {
    const double h = 1e-6 * std::max(1.0, std::abs(x0[col]));
    Eigen::Vector4d plus = x0, minus = x0;
    plus[col] += h;
    minus[col] -= h;
    J.col(col) = (rates(plus) - rates(minus)) / (2 * h);
  }
  return J;
}

// -lambda^2 of the Jacobian's eigenvalue of largest size (the other two are 0, 0): K.
double stiffnessFromJacobian(const Eigen::Matrix4d& J) {
  std::complex<double> dominant = 0;
  for (const auto& lambda : Eigen::Vector4cd(J.eigenvalues())) {
    if (std::abs(lambda) > std::abs(dominant)) dominant = lambda;
  }
  return -(dominant * dominant).real();
}

// The steady circles the thick tests run over: both rims, both sides of upright, both branches; a cornered rim
// below its balance angle may have none at low spin (checked in CorneredRimBelowItsBalanceAngleNeedsSpin).
template <typename Check>
int forEachThickCircle(const Check& check) {
  int count = 0;
  for (const CoinModel& m : thickCoins()) {
    for (double thetaDeg : {-60.0, -10.0, 0.0, 1.0, 5.0, 10.0, 30.0, 60.0, 85.0}) {
      if (thetaDeg == 0 && hasCorners(m)) continue;
      for (double spin : {0.3, 2.0, 8.0}) {
        for (int branch : {+1, -1}) {
          if (thetaDeg == 0 && branch == -1) continue;
          const CoinState s = steadyCircle(m, thetaDeg * kDeg, spin * naturalRate(m), branch);
          check(m, s,
                ::testing::Message() << "rho " << m.rim.edgeRadius << " theta " << thetaDeg << " spin " << spin
                                     << " branch " << branch);
          ++count;
        }
      }
    }
  }
  return count;
}

TEST(ThickSteadyStates, CirclesSatisfyTheResidualAndTheReferenceEquations) {
  const int count = forEachThickCircle([](const CoinModel& m, const CoinState& s, const ::testing::Message& where) {
    EXPECT_TRUE(isBelow(std::abs(steadyResidual(m, s)) / residualScale(m, s), 1e-13)) << where;
    EXPECT_TRUE(isBelow(referenceDrift(m, s), 1e-12)) << where;
  });
  EXPECT_EQ(count, 2 * (8 * 3 * 2 + 3) - 3);
}

TEST(ThickSteadyStates, CirclesAreFixedPointsOfTheRatesOfTheDynamics) {
  // physics::rates with a rim (docs/rim.md §2): d(theta) and d(omega) vanish to round-off.
  forEachThickCircle([](const CoinModel& m, const CoinState& s, const ::testing::Message& where) {
    EXPECT_TRUE(isBelow(steadyDrift(m, s), 1e-12)) << where;
  });
}

TEST(ThickSteadyStates, CorneredRimBelowItsBalanceAngleNeedsSpin) {
  // docs/rim.md eq. 5.2: below the balance angle gravity rights the coin (Lambda < 0), and a steady circle
  // needs |omega_Z| >= sqrt(-4 P M g Lambda) / Q (2.3 rad/s for the toy at 3 degrees).
  const CoinModel m = thickDisk(0.0016);
  EXPECT_TRUE(isNear(balanceAngle(m) / kDeg, 7.7723, 1e-4));
  EXPECT_THROW(steadyCircle(m, 3 * kDeg, 1.0, +1), std::invalid_argument);
  EXPECT_THROW(steadyCircle(m, -3 * kDeg, 1.0, -1), std::invalid_argument);
  for (int branch : {+1, -1}) {
    const CoinState s = steadyCircle(m, 3 * kDeg, 10.0, branch);
    EXPECT_TRUE(isBelow(referenceDrift(m, s), 1e-12)) << branch;
    // Both roots have the sign of -omega_Z (their product M g Lambda / P > 0, their sum -Q omega_Z / P < 0).
    EXPECT_LT(s.omega_Y, 0) << branch;
  }
  // Just above the balance angle every spin has its two circles again.
  EXPECT_NO_THROW(steadyCircle(m, balanceAngle(m) + 1e-3, 0.1, +1));
}

TEST(ThickSteadyStates, SpinInPlaceKeepsTheCentreOfMassAtRest) {
  for (const CoinModel& m : thickCoins()) {
    // A cornered rim has none between its balance angle (7.77 deg) and I_X A tan = I_Z B (15.29 deg): eq. 5.3.
    for (double thetaDeg : {-40.0, 3.0, 5.0, 20.0, 30.0, 70.0, 89.0}) {
      const CoinState s = spinInPlace(m, thetaDeg * kDeg);
      const ::testing::Message where = ::testing::Message() << "rho " << m.rim.edgeRadius << " theta " << thetaDeg;
      EXPECT_GT(s.omega_Y, 0) << where;
      EXPECT_TRUE(isBelow(std::abs(steadyResidual(m, s)) / residualScale(m, s), 1e-13)) << where;
      EXPECT_TRUE(isBelow(referenceDrift(m, s), 1e-12)) << where;
      const Eigen::Vector3d omega(s.omega_X, s.omega_Y, s.omega_Z);
      const Eigen::Vector3d c = referenceContact(m, s.theta);
      EXPECT_TRUE(isBelow(c.cross(omega).norm(), 1e-15)) << where;  // omega along c: v = 0
      const Eigen::Vector3d up(0, std::cos(s.theta), -std::sin(s.theta));
      const CircleRadii radii = circleRadii(m, s);
      EXPECT_TRUE(isBelow(radii.centreOfMass, 1e-15)) << where;
      EXPECT_TRUE(isNear(radii.contact, c.cross(up).norm(), 1e-15)) << where;  // |Lambda|, eq. 5.10
    }
  }
  EXPECT_THROW(spinInPlace(thickDisk(0.0016), 10 * kDeg), std::invalid_argument);
  EXPECT_THROW(spinInPlace(thickDisk(0.0016), -12 * kDeg), std::invalid_argument);
  EXPECT_THROW(spinInPlace(thickDisk(0.0065), 0.0), std::invalid_argument);
}

TEST(ThickSteadyStates, SpinInPlaceIsAtRestInTheDynamics) {
  // physics::rates, centreOfMassVelocity and reaction with a rim: steady, G at rest, the floor pushes the weight.
  for (const CoinModel& m : thickCoins()) {
    for (double thetaDeg : {3.0, 30.0, 70.0}) {
      const CoinState s = spinInPlace(m, thetaDeg * kDeg);
      EXPECT_TRUE(isBelow(steadyDrift(m, s), 1e-12)) << thetaDeg;
      EXPECT_TRUE(isBelow(centreOfMassVelocity(m, s).norm(), 1e-15)) << thetaDeg;
      const Reaction r = reaction(m, s);
      EXPECT_TRUE(isNear(r.N, m.M * m.g, 1e-12 * m.M * m.g)) << thetaDeg;
      EXPECT_TRUE(isBelow(r.F, 1e-12 * m.M * m.g)) << thetaDeg;
    }
  }
}

TEST(ThickSteadyStates, CircleRadiiAreThoseOfTheCirclesTheCentreAndTheContactRun) {
  // In a steady motion XYZ turns rigidly about a vertical axis at phi-dot, so a point moving at v circles at
  // r = -(y_hat x v) / phi-dot from it. G (v = c x omega) and the contact point (G + c, moving at v + Omega x c)
  // must lie on circles about the same axis, with the radii of circleRadii.
  forEachThickCircle([](const CoinModel& m, const CoinState& s, const ::testing::Message& where) {
    if (s.omega_Y == 0) return;  // straight rolling: infinite radii
    const Eigen::Vector3d omega(s.omega_X, s.omega_Y, s.omega_Z);
    const Eigen::Vector3d frameRate(0, s.omega_Y, -s.omega_Y * std::tan(s.theta));
    const Eigen::Vector3d up(0, std::cos(s.theta), -std::sin(s.theta));
    const Eigen::Vector3d c = referenceContact(m, s.theta);
    const double phiDot = s.omega_Y / std::cos(s.theta);
    const Eigen::Vector3d v = c.cross(omega), vContact = v + frameRate.cross(c);
    const Eigen::Vector3d fromAxisToCentre = -up.cross(v) / phiDot;
    const Eigen::Vector3d fromAxisToContact = fromAxisToCentre + (c - c.dot(up) * up);
    EXPECT_TRUE(isBelow((fromAxisToContact + up.cross(vContact) / phiDot).norm(), 1e-12 * m.a)) << where;
    const CircleRadii radii = circleRadii(m, s);
    EXPECT_TRUE(isNear(radii.centreOfMass / fromAxisToCentre.norm(), 1.0, 1e-12)) << where;
    EXPECT_TRUE(isNear(radii.contact / fromAxisToContact.norm(), 1.0, 1e-12)) << where;
  });
}

TEST(ThickSteadyStates, FullyRoundedRimRollsStraightAndUpright) {
  const CoinModel m = thickDisk(kToyThickness / 2);
  for (double omega_Z : {-5.0, 0.0, 12.0}) {
    const CoinState s = straightRolling(m, omega_Z);
    EXPECT_EQ(s.theta, 0);
    EXPECT_EQ(s.omega_Y, 0);
    EXPECT_EQ(s.omega_Z, omega_Z);
    EXPECT_EQ(steadyCircle(m, 0, omega_Z, +1).omega_Y, 0);
    EXPECT_EQ(steadyResidual(m, s), 0);
    EXPECT_TRUE(isBelow(referenceDrift(m, s), 1e-15));
  }
  EXPECT_THROW(steadyCircle(m, 0, 12.0, -1), std::invalid_argument);
  // docs/rim.md eq. 5.9 for the toy: omega_c^2 = M g (a - rho) I_X / (I_Z (I_Z + M a^2)), 8.6587 rad/s against
  // the thin disk's sqrt(g / (3 a)) = 9.3381 rad/s.
  const double Ma2 = m.M * m.a * m.a, rho = m.rim.edgeRadius;
  const double omega_c = criticalSpin(m);
  EXPECT_TRUE(isNear(omega_c, std::sqrt(m.M * m.g * (m.a - rho) * m.I_X / (m.I_Z * (m.I_Z + Ma2))), 1e-14));
  EXPECT_TRUE(isNear(omega_c, 8.658696113741575, 1e-12));
  EXPECT_TRUE(isNear(criticalSpin(diskModel(0.4, kToyRadius, 9.81)), 9.338094023943002, 1e-12));
  EXPECT_LT(wobbleStiffness(m, 0, 0, 0.999 * omega_c), 0);
  EXPECT_GT(wobbleStiffness(m, 0, 0, 1.001 * omega_c), 0);
  for (double omega_Z : {0.5 * omega_c, 2 * omega_c}) {
    const double expected =
        ((m.I_Z + Ma2) * m.I_Z * omega_Z * omega_Z / m.I_X - m.M * m.g * (m.a - rho)) / (m.I_X + Ma2);
    EXPECT_TRUE(isNear(wobbleStiffness(m, 0, 0, omega_Z) / expected, 1.0, 1e-14)) << omega_Z;
  }
}

TEST(ThickSteadyStates, CorneredRimRefusesUprightMotions) {
  // docs/rim.md eq. 5.4: upright the contact switches corners, so no straight rolling, no critical spin and no K.
  const CoinModel m = thickDisk(0.0016);
  const auto expectCornerError = [](const auto& call, const char* what) {
    try {
      call();
      ADD_FAILURE() << what << " did not throw";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("corner"), std::string::npos) << what << ": " << error.what();
    }
  };
  expectCornerError([&] { criticalSpin(m); }, "criticalSpin");
  expectCornerError([&] { straightRolling(m, 12.0); }, "straightRolling");
  expectCornerError([&] { steadyCircle(m, 0, 12.0, +1); }, "steadyCircle +");
  expectCornerError([&] { steadyCircle(m, 0, 12.0, -1); }, "steadyCircle -");
  expectCornerError([&] { wobbleStiffness(m, 0, 0, 12.0); }, "wobbleStiffness");
  // Upright the residual is gravity's torque about the touching corner, M g (h/2 - rho) (eq. 5.4).
  EXPECT_TRUE(isNear(steadyResidual(m, straightRolling(12.0)), m.M * m.g * (m.rim.thickness / 2 - 0.0016), 1e-15));
  // Thin and fully rounded coins roll upright.
  EXPECT_NO_THROW(straightRolling(diskModel(0.4, kToyRadius, 9.81), 12.0));
  EXPECT_NO_THROW(straightRolling(thickDisk(kToyThickness / 2), 12.0));
}

TEST(ThickWobbleStiffness, MatchesTheEigenvaluesOfTheReferenceJacobian) {
  forEachThickCircle([](const CoinModel& m, const CoinState& s, const ::testing::Message& where) {
    const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
    const auto rates = [&m](const Eigen::Vector4d& x) { return referenceTiltRates(m, x); };
    EXPECT_TRUE(isNear(stiffnessFromJacobian(centralJacobian(rates, tiltVector(s))) / K, 1.0, 1e-6))
        << where << " K " << K;
  });
}

TEST(ThickWobbleStiffness, MatchesTheEigenvaluesOfTheNumericalJacobianOfTheDynamics) {
  // As WobbleStiffness.MatchesTheEigenvaluesOfTheNumericalJacobian, through physics::rhs with a rim.
  forEachThickCircle([](const CoinModel& m, const CoinState& s, const ::testing::Message& where) {
    const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
    EXPECT_TRUE(isNear(stiffnessFromJacobian(tiltJacobian(m, s)) / K, 1.0, 1e-6)) << where << " K " << K;
  });
}

TEST(ThickWobbleStiffness, SpinInPlaceMatchesTheReferenceJacobian) {
  for (const CoinModel& m : thickCoins()) {
    for (double thetaDeg : {3.0, 30.0, 70.0}) {
      const CoinState s = spinInPlace(m, thetaDeg * kDeg);
      const double K = wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
      const auto rates = [&m](const Eigen::Vector4d& x) { return referenceTiltRates(m, x); };
      EXPECT_TRUE(isNear(stiffnessFromJacobian(centralJacobian(rates, tiltVector(s))) / K, 1.0, 1e-6)) << thetaDeg;
    }
  }
}

TEST(ThickWobbleStiffness, TendsToTheThinCoinsAsTheThicknessVanishes) {
  // Same moments, rim geometry shrinking: the steady state and K of docs/rim.md eq. 5.8 approach derivations
  // (3.1) and (3.6), the difference shrinking like h / a (up to 25 h / a: the f- branch at 5 degrees, cornered).
  for (double edgeFraction : {0.5, 0.25}) {
    for (double thetaDeg : {5.0, 30.0, 70.0}) {
      for (int branch : {+1, -1}) {
        double previous = std::numeric_limits<double>::infinity();
        for (double h : {1e-3, 1e-5, 1e-7}) {
          const CoinModel thick = thickDisk(edgeFraction * h, h);
          CoinModel thin = thick;
          thin.rim = {};
          const double omega_Z = 2 * naturalRate(thin);
          const CoinState sThick = steadyCircle(thick, thetaDeg * kDeg, omega_Z, branch);
          const CoinState sThin = steadyCircle(thin, thetaDeg * kDeg, omega_Z, branch);
          const double KThin = wobbleStiffness(thin, sThin.theta, sThin.omega_Y, sThin.omega_Z);
          const double difference =
              std::abs(wobbleStiffness(thick, sThick.theta, sThick.omega_Y, sThick.omega_Z) / KThin - 1);
          const ::testing::Message where = ::testing::Message() << "rho/h " << edgeFraction << " theta " << thetaDeg
                                                                << " branch " << branch << " h " << h;
          // First order in h / a: each hundredfold thinner coin is (at least fifty times) closer.
          EXPECT_TRUE(isBelow(difference, 100 * h / thick.a)) << where;
          EXPECT_TRUE(isNear(sThick.omega_Y / sThin.omega_Y, 1.0, 100 * h / thick.a)) << where;
          EXPECT_LT(difference, previous / 50) << where;
          previous = difference;
        }
      }
    }
  }
}

}  // namespace
}  // namespace coinroll::physics

namespace coinroll::physics {
namespace {

// The verdict `coinroll steady` prints: K's sign decides, sqrt(|K|) gives the rate and the time.
TEST(TiltStability, TheSignOfKDecidesAndItsRootGivesTheTimes) {
  const TiltStability stable = tiltStability(4);
  EXPECT_EQ(stable.kind, TiltStability::Kind::Stable);
  EXPECT_DOUBLE_EQ(stable.rate, 2);
  EXPECT_DOUBLE_EQ(stable.time, std::numbers::pi);  // the period 2 pi / 2
  const TiltStability unstable = tiltStability(-0.25);
  EXPECT_EQ(unstable.kind, TiltStability::Kind::Unstable);
  EXPECT_DOUBLE_EQ(unstable.rate, 0.5);
  EXPECT_DOUBLE_EQ(unstable.time, 2);  // the e-folding time 1 / 0.5
  const TiltStability marginal = tiltStability(0);
  EXPECT_EQ(marginal.kind, TiltStability::Kind::Marginal);
  EXPECT_EQ(marginal.rate, 0);
  EXPECT_EQ(marginal.time, 0);
}

// Straight rolling above the critical spin is stable, below it unstable (seed 5.1): the verdict
// follows K across omega_c.
TEST(TiltStability, StraightRollingTurnsStableAtTheCriticalSpin) {
  const CoinModel disk = diskModel(0.4, 0.0375, 9.81);
  const double omega_c = criticalSpin(disk);
  const auto verdictAt = [&](double omega_Z) {
    const CoinState s = straightRolling(disk, omega_Z);
    return tiltStability(wobbleStiffness(disk, s.theta, s.omega_Y, s.omega_Z)).kind;
  };
  EXPECT_EQ(verdictAt(1.01 * omega_c), TiltStability::Kind::Stable);
  EXPECT_EQ(verdictAt(0.99 * omega_c), TiltStability::Kind::Unstable);
}

}  // namespace
}  // namespace coinroll::physics
