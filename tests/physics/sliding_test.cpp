// The sliding coin's forward pass (docs/sliding.md) against closed forms: Painleve's normal
// effective mass (3.2) and the normal force of a coin sliding without rotating; and the rules of
// the switches between rolling and sliding (physics/contact_mode.h).

#include "physics/sliding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "physics/coin_model.h"
#include "physics/contact_mode.h"
#include "physics/observables.h"
#include "physics/quaternion_dynamics.h"
#include "reference_solver.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;

using reference::kDeg;

TEST(Sliding, NormalEffectiveMassIsPainlevesClosedForm) {
  // Thin disk, heading phi = 0: h = e_X x e_y is +z. D = 1 + (M / I_X)(Lambda^2 + mu Lambda H (s_hat . h)) with
  // Lambda = a sin(theta), H = a cos(theta) (docs/sliding.md eq. 3.3); a slip along -z (away from under G)
  // makes it negative above mu = 1.118 at 24 degrees.
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  for (const double theta : {5.0, 24.0, 50.0}) {
    for (const double mu : {0.3, 1.0, 2.0}) {
      for (const double along : {-1.0, 1.0}) {
        const CoinState s{.theta = theta * kDeg};
        const QuaternionState q = fromEulerState(s);
        const Forward f =
            slidingForward(m, {.attitude = q, .slip = Eigen::Vector2d(0, along)}, mu, Eigen::Vector3d::UnitZ());
        const double Lambda = m.a * std::sin(s.theta), H = m.a * std::cos(s.theta);
        const double expected = 1 + m.M / m.I_X * (Lambda * Lambda + mu * Lambda * H * along);
        EXPECT_TRUE(isNear(f.normalEffectiveMass, expected, 1e-13))
            << theta << " deg, mu " << mu << ", along " << along;
      }
    }
  }
}

TEST(Sliding, AnUprightCoinSlidingWithoutRotationPressesWithItsWeightAndIsBrakedAtMuG) {
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const QuaternionState q = fromEulerState(CoinState{});
  const Forward f = slidingForward(m, {.attitude = q, .slip = Eigen::Vector2d(1.0, 0)}, 0.3, Eigen::Vector3d::UnitX());
  EXPECT_TRUE(isNear(f.reaction.N, m.M * m.g, 1e-13));
  EXPECT_TRUE(isNear(f.reaction.R.x(), -0.3 * m.M * m.g, 1e-13));
  EXPECT_TRUE(isNear(f.loads.power, 0.3 * m.M * m.g * 1.0, 1e-13));  // mu N |s|
  // The friction torque about G spins the disk up: I_Z omega-dot = mu M g a about the axis.
  EXPECT_TRUE(isNear(std::abs(f.dOmega.z()), 0.3 * m.M * m.g * m.a / m.I_Z, 1e-10));
}

TEST(ContactMode, AStartWithASlipSlidesAndOtherwiseRollsWhereTheRollingReactionFitsTheStaticCone) {
  CoinModel m = diskModel(0.4, 0.0375, 9.81);
  m.friction = {.cone = 0.4, .kinetic = 0.3};
  // Tilted and at rest the coin falls, and rolling needs friction to hold its contact point.
  const QuaternionState q = fromEulerState(CoinState{.theta = 25 * kDeg});
  const Forward rolling = forward(m, q);
  const Handover slipStops{.t = 0.5, .state = {.attitude = q}, .forward = rolling};
  EXPECT_EQ(heldMode(m, {.attitude = q, .slip = Eigen::Vector2d(0.1, 0)}), Mode::Sliding);
  ASSERT_GT(rolling.reaction.F, 0);
  ASSERT_GT(rolling.reaction.N, 0);
  const double needed = rolling.reaction.F / rolling.reaction.N;
  m.friction.cone = 0.5 * needed;
  EXPECT_LT(slideOnsetMargin(m, rolling), 0);
  EXPECT_EQ(heldMode(m, {.attitude = q}), Mode::Creeping);
  EXPECT_EQ(next(m, Mode::Sliding, Transition::SlipStops, slipStops), Next(Mode::Creeping));
  m.friction.cone = 2 * needed;
  EXPECT_GT(slideOnsetMargin(m, rolling), 0);
  EXPECT_EQ(heldMode(m, {.attitude = q}), Mode::Rolling);
  EXPECT_EQ(next(m, Mode::Sliding, Transition::SlipStops, slipStops), Next(Mode::Rolling));
  // A slip stops at 1e-11 m/s up to t = 1 s, a threshold growing with t after. 10 atol at the
  // default atol (1e-12) is that threshold; a looser atol raises it to what the integrator holds.
  constexpr double kDefaultResolved = 10 * 1e-12;
  EXPECT_GT(slipStopMargin(0.5, Eigen::Vector2d(5e-10, 0), Eigen::Vector2d::Zero(), kDefaultResolved), 0);
  EXPECT_LT(slipStopMargin(0.5, Eigen::Vector2d(5e-10, 0), Eigen::Vector2d::Zero(), 10 * 1e-10), 0);
  EXPECT_LT(
      creepStopMargin(0.5, Eigen::Vector2d(5e-10, 0), Eigen::Vector2d::Zero(), 10 * 1e-10, Eigen::Vector3d::UnitX()),
      0);
  EXPECT_LT(slipStopMargin(0.5, Eigen::Vector2d(0.5e-11, 0), Eigen::Vector2d::Zero(), kDefaultResolved), 0);
  EXPECT_GT(slipStopMargin(0.5, Eigen::Vector2d(0, 2e-11), Eigen::Vector2d::Zero(), kDefaultResolved), 0);
  EXPECT_LT(slipStopMargin(10, Eigen::Vector2d(0, 2e-11), Eigen::Vector2d::Zero(), kDefaultResolved), 0);
  // A hard skid's slip, closing at 3 mu g (mu = 2000), ends once it would stop within 1e-13 s: at
  // 5.9e-9 m/s, not at 1e-11 m/s, where its steps stalled (docs/sliding.md §4.5, "Hard skids"); an
  // opening slip does not end.
  const Eigen::Vector2d hardClosing(-3 * 2000 * 9.81, 0);
  EXPECT_LT(slipStopMargin(0.5, Eigen::Vector2d(5e-9, 0), hardClosing, kDefaultResolved), 0);
  EXPECT_GT(slipStopMargin(0.5, Eigen::Vector2d(7e-9, 0), hardClosing, kDefaultResolved), 0);
  EXPECT_GT(slipStopMargin(0.5, Eigen::Vector2d(5e-9, 0), -hardClosing, kDefaultResolved), 0);
  EXPECT_LT(creepStopMargin(0.5, Eigen::Vector2d(5e-9, 0), hardClosing, kDefaultResolved, Eigen::Vector3d::UnitX()), 0);
  EXPECT_GT(creepStopMargin(0.5, Eigen::Vector2d(7e-9, 0), hardClosing, kDefaultResolved, Eigen::Vector3d::UnitX()), 0);
}

// s_perp . s-dot with friction along -slipHat: the slip's turn rate times |s| (docs/sliding.md §4.6).
double turningAlong(const CoinModel& m, const SlidingStateVec& y, double mu, const Eigen::Vector3d& slipHat) {
  const SlidingStateVec dy = slidingRatesAlong(m, y, mu, slipHat).dy;
  return -slipHat.z() * dy[kSlipX] + slipHat.x() * dy[kSlipZ];
}

Eigen::Vector3d alongAngle(double angle) { return {std::cos(angle), 0, std::sin(angle)}; }

// The creeping slide's friction direction against its defining equations, each checked another way:
// the rest turns the slip at nothing, the lagging direction as (4.17) says, the restoring is the slope
// there, the rest's rate is the difference of the rests found at states a little before and after
// along the motion, and the pull is the restoring plus the slip's rate along the rest.
TEST(Creep, TheRestAndItsLagSolveTheirEquations) {
  CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const double mu = 0.2;
  int checked = 0;
  for (const double theta : {15.0, 25.0, 40.0}) {
    for (const double slipAngle : {0.3, 2.0, -1.2}) {
      const QuaternionState q =
          fromEulerState(CoinState{.theta = theta * kDeg, .omega_X = -0.5, .omega_Y = 3.0, .omega_Z = 9.0});
      SlidingStateVec y = toVector(SlidingState{.attitude = q});
      const std::optional<Creep> rest = findCreep(m, y, mu);
      if (!rest) continue;
      const double restAngle = std::atan2(rest->slipHat.z(), rest->slipHat.x());
      EXPECT_TRUE(isBelow(std::abs(turningAlong(m, y, mu, rest->slipHat)) / rest->restoring, 1e-12)) << theta;
      constexpr double kAngleStep = 1e-5;
      const double slope = -(turningAlong(m, y, mu, alongAngle(restAngle + kAngleStep)) -
                             turningAlong(m, y, mu, alongAngle(restAngle - kAngleStep))) /
                           (2 * kAngleStep);
      EXPECT_TRUE(isNear(rest->restoring, slope, 1e-6 * std::abs(slope))) << theta;
      constexpr double kTimeStep = 1e-5;
      const SlidingStateVec flow = slidingRatesAlong(m, y, mu, rest->slipHat).dy;
      const auto restAngleAt = [&](double dt) {
        SlidingStateVec moved = y + dt * flow;
        moved.tail<2>().setZero();
        const Eigen::Vector3d hat = findCreep(m, moved, mu).value().slipHat;
        return std::atan2(hat.z(), hat.x());
      };
      const double restRate = (restAngleAt(kTimeStep) - restAngleAt(-kTimeStep)) / (2 * kTimeStep);
      EXPECT_TRUE(isNear(rest->restRate, restRate, 1e-5 * std::abs(restRate) + 1e-9)) << theta;
      const double slipRate = rest->slipHat.x() * flow[kSlipX] + rest->slipHat.z() * flow[kSlipZ];
      EXPECT_TRUE(isNear(rest->pull, rest->restoring + slipRate, 1e-12 * rest->restoring)) << theta;
      // A creeping slip of 1e-6 m/s lags its rest: friction along the lagging direction turns it as
      // the slip along the rest, sigma, times the rest's rate, pulled by K / P (eq. 4.17).
      y.tail<2>() = 1e-6 * Eigen::Vector2d(std::cos(slipAngle), std::sin(slipAngle));
      const double sigma = y[kSlipX] * rest->slipHat.x() + y[kSlipZ] * rest->slipHat.z();
      const std::optional<Creep> lagging = findCreep(m, y, mu);
      ASSERT_TRUE(lagging) << theta;
      const double target = sigma * lagging->restRate * lagging->restoring / lagging->pull;
      EXPECT_TRUE(isBelow(std::abs(turningAlong(m, y, mu, lagging->slipHat) - target) / lagging->restoring, 1e-12))
          << theta;
      EXPECT_GT(std::abs(target) / lagging->restoring, 1e-9) << theta;  // the lag is not lost in the check
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
}

}  // namespace
}  // namespace coinroll::physics
