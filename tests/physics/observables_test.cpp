#include "physics/observables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/dynamics.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;

constexpr double kRotationTolerance = 1e-14;  // a product of three unit quaternions, round-off only

CoinState generalState() {
  return {.theta = 0.4, .phi = -1.1, .psi = 2.3, .omega_X = 0.7, .omega_Y = -1.9, .omega_Z = 5.2, .x = 0.1, .z = -0.2};
}

TEST(Attitude, RotatesBodyAxesOntoRowsOfR) {
  for (double theta : {-1.2, -0.3, 0.0, 0.5, 1.4}) {
    for (double phi : {-2.5, 0.0, 0.8, 3.0}) {
      const CoinState s{.theta = theta, .phi = phi, .psi = 0.0};
      const Eigen::Matrix3d rotated = attitude(s).toRotationMatrix();  // columns: images of e_x, e_y, e_z
      const Eigen::Matrix3d R = coinAxesInFloor(s);
      EXPECT_TRUE(isBelow((rotated.transpose() - R).cwiseAbs().maxCoeff(), kRotationTolerance));
    }
  }
}

TEST(Attitude, SpinRotatesAboutTheCoinNormal) {
  CoinState s = generalState();
  const Eigen::Vector3d normalBefore = attitude(s) * Eigen::Vector3d::UnitZ();
  s.psi += 1.0;
  const Eigen::Vector3d normalAfter = attitude(s) * Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(isBelow((normalBefore - normalAfter).norm(), kRotationTolerance));
  EXPECT_TRUE(isBelow((normalAfter - coinAxesInFloor(s).row(2).transpose()).norm(), kRotationTolerance));
}

TEST(ContactPoint, LiesOnTheFloorOneRadiusFromTheCentre) {
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const CoinState s = generalState();
  const Eigen::Vector3d c = contactPoint(m, s);
  EXPECT_TRUE(isNear(c.y(), 0.0, 1e-17));
  EXPECT_TRUE(isNear((c - centreOfMass(m, s)).norm(), m.a, 1e-16));
}

// d/dt of a function of state along the flow, by a central difference of the RHS direction.
template <class F>
Eigen::Vector3d rateAlongFlow(const CoinModel& m, const CoinState& s, F observable) {
  const double h = 1e-6;
  const StateVec y = toVector(s), dy = rhs(m, 0, y);
  return (observable(toState(y + h * dy)) - observable(toState(y - h * dy))) / (2 * h);
}

TEST(ContactPoint, MovesAtRadiusTimesSpinRate) {
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const CoinState s = generalState();
  const Eigen::Vector3d contactVelocity = rateAlongFlow(m, s, [&](const CoinState& q) { return contactPoint(m, q); });
  EXPECT_TRUE(isNear(contactVelocity.norm(), m.a * std::abs(spinRate(s)), 1e-9));
}

TEST(CentreOfMassVelocity, IsTheTimeDerivativeOfThePosition) {
  const CoinModel m = ringModel(0.4, 0.0375, 0.02, 9.81);
  const CoinState s = generalState();
  const Eigen::Vector3d numeric = rateAlongFlow(m, s, [&](const CoinState& q) { return centreOfMass(m, q); });
  EXPECT_TRUE(isBelow((numeric - centreOfMassVelocity(m, s)).norm(), 1e-9));
}

TEST(Energy, IsConstantAlongTheFlowForDiskRingAndCustom) {
  const CoinModel models[] = {diskModel(0.4, 0.0375, 9.81),
                              ringModel(0.4, 0.0375, 0.01, 9.81),
                              {.M = 0.01, .a = 0.012, .g = 9.81, .I_X = 5e-7, .I_Z = 8e-7, .rim = {}, .effects = {}}};
  for (const CoinModel& m : models) {
    const CoinState s = generalState();
    const double h = 1e-6;
    const StateVec y = toVector(s), dy = rhs(m, 0, y);
    const double dE = (energy(m, toState(y + h * dy)) - energy(m, toState(y - h * dy))) / (2 * h);
    // The kinetic energy rates are O(M a^2 omega^3); compare dE/dt to that scale.
    const double scale = m.M * m.a * m.a * std::pow(5.2, 3);
    EXPECT_TRUE(isBelow(std::abs(dE) / scale, 1e-8));
  }
}

TEST(Reaction, UprightCoinAtRestCarriesItsWeight) {
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const Reaction r = reaction(m, CoinState{});
  EXPECT_TRUE(isNear(r.N, m.M * m.g, 1e-15));
  EXPECT_TRUE(isNear(r.F, 0.0, 1e-15));
}

TEST(Reaction, EqualsMassTimesAccelerationPlusWeight) {
  // R = M dv/dt + M g e_y with dv/dt differentiated numerically along the flow: an independent
  // check of the closed form (seed section 4, docs/seed.md §3).
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const CoinState s = generalState();
  const Eigen::Vector3d acceleration =
      rateAlongFlow(m, s, [&](const CoinState& q) { return centreOfMassVelocity(m, q); });
  const Eigen::Vector3d expected = m.M * acceleration + Eigen::Vector3d(0, m.M * m.g, 0);
  const Reaction r = reaction(m, s);
  EXPECT_TRUE(isBelow((r.R - expected).norm() / (m.M * m.g), 1e-8));
  EXPECT_TRUE(isNear(r.N, expected.y(), 1e-8 * m.M * m.g));
  EXPECT_TRUE(isNear(r.F, std::hypot(expected.x(), expected.z()), 1e-8 * m.M * m.g));
}

}  // namespace
}  // namespace coinroll::physics
