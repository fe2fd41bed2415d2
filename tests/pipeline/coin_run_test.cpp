// The run driver against a truth computed another way: the Euler-angle formulation for the
// quaternion run's unwrapped angles.

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "pipeline/coin_run.h"
#include "pipeline/simulation.h"
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
