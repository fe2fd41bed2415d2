// The run driver against a truth computed another way: the Euler-angle formulation for the
// quaternion run's unwrapped angles.

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "pipeline/coin_run.h"
#include "pipeline/simulation.h"
#include "pipeline/validity_events.h"
#include "scene/scene_loader.h"
#include "tolerance.h"

namespace {

using namespace coinroll;
using coinroll::testing::isNear;

pipeline::Simulation wobblingToy(std::string_view formulation) {
  nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
      {"initial", {{"theta", 20}, {"omega_X", 0.5}, {"omega_Y", 3.0}, {"omega_Z", 14.0}}},
      {"duration", 4.0},
      {"solver", {{"formulation", formulation}, {"rtol", 1e-12}, {"atol", 1e-14}}},
  };
  return pipeline::buildSimulation(scene::parseScene(doc, "test"));
}

TEST(CoinRun, QuaternionRunUnwrapsPhiAndPsiLikeTheEulerAnglesBetweenSparseQueries) {
  // The quaternion carries phi and psi only modulo 2 pi; the run must keep them continuous however
  // far apart the queries are. psi turns about 15 rad/s here, so a query every 0.5 s skips more
  // than a turn; the Euler-angle formulation integrates phi and psi directly and is the truth.
  pipeline::CoinRun euler(wobblingToy("euler-angles")), quaternion(wobblingToy("quaternion"));
  for (int k = 1; k <= 8; ++k) {
    const double t = 0.5 * k;
    const physics::CoinState e = *euler.stateAt(t), q = *quaternion.stateAt(t);
    EXPECT_TRUE(isNear(q.phi, e.phi, 1e-6)) << "t = " << t;
    EXPECT_TRUE(isNear(q.psi, e.psi, 1e-6)) << "t = " << t;
    EXPECT_TRUE(isNear(q.theta, e.theta, 1e-6)) << "t = " << t;
  }
}

}  // namespace

namespace coinroll::pipeline {
namespace {

// The events' shared forward pass: what it returns is the pass itself, and it runs the pass once per
// state among the last kConeGrazeChecks + 1 states (a step's interior checks and its end).
TEST(RememberedForward, ReturnsThePassAndRunsItOncePerRecentState) {
  using Y = integrate::Vec<3>;
  int passes = 0;
  const auto forward = remembering<3>([&passes](const Y& y) {
    ++passes;
    physics::Forward f;
    f.energy = y.sum();
    return f;
  });
  const auto copy = forward;  // a second event of the same segment
  const Y a(1, 2, 3), b(4, 5, 6), c(7, 8, 9), d(1, 1, 1), e(2, 2, 2);
  EXPECT_EQ(forward(a).energy, 6);
  EXPECT_EQ(copy(a).energy, 6);
  EXPECT_EQ(passes, 1);
  for (const Y& y : {b, c, d}) copy(y);
  EXPECT_EQ(forward(a).energy, 6);
  EXPECT_EQ(passes, 4);
  forward(e);  // five states: the oldest, a, is forgotten
  EXPECT_EQ(forward(a).energy, 6);
  EXPECT_EQ(passes, 6);
  // -0 and +0 are different bits: the memo compares bits, not values.
  forward(Y(0, 0, 0));
  forward(Y(-0.0, 0, 0));
  EXPECT_EQ(passes, 8);
}

}  // namespace
}  // namespace coinroll::pipeline
