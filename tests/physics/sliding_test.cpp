// The sliding coin's forward pass (docs/sliding.md) against closed forms: Painleve's normal
// effective mass (3.2) and the normal force of a coin sliding without rotating.

#include "physics/sliding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/coin_model.h"
#include "physics/observables.h"
#include "reference_solver.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

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

}  // namespace
}  // namespace coinroll::physics
