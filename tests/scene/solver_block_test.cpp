// The scene's solver block: the method resolved to its type once, by the loader; defaults and
// ranges the integrator's, named in the messages as the README gives them.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

#include "integrate/solver_config.h"
#include "scene/scene_loader.h"

namespace coinroll::scene {
namespace {

SceneConfig withSolver(const nlohmann::json& solver) {
  nlohmann::json document = builtInDefaultScene();
  document["solver"] = solver;
  return parseScene(document, "scene.json");
}

std::string refusal(const nlohmann::json& solver) {
  try {
    withSolver(solver);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SolverBlock, TheMethodIsResolvedToItsType) {
  EXPECT_EQ(withSolver(nlohmann::json::object()).solver.method, integrate::SolverConfig{}.method);
  for (const std::string_view name : integrate::methodNames()) {
    EXPECT_EQ(integrate::nameOf(withSolver({{"method", name}}).solver.method), name);
  }
  EXPECT_EQ(refusal({{"method", "rk45"}}),
            "scene.json: solver.method: unknown method \"rk45\"; available: euler, rk4, dopri5, dop853, gauss4");
}

TEST(SolverBlock, RangesAreNamedWithTheirDefaults) {
  EXPECT_EQ(refusal({{"rtol", 0}}), "scene.json: solver.rtol: must be in [1e-14, 1e-2] (default 1e-10), got 0");
  EXPECT_EQ(refusal({{"atol", 0.1}}),
            "scene.json: solver.atol: must be in (0, 1e-2] (default 1e-12; 0 cannot weigh a state component that is "
            "0), got 0.1");
  EXPECT_EQ(refusal({{"dt", 2}}), "scene.json: solver.dt: must be in [1e-7, 1] s (default 1e-3), got 2");
  EXPECT_EQ(refusal({{"formulation", "euler"}}),
            "scene.json: solver.formulation: unknown formulation \"euler\"; available: euler-angles, quaternion");
  EXPECT_EQ(
      withSolver({{"rtol", integrate::kMinRtol}, {"atol", integrate::kMaxAtol}, {"dt", integrate::kMaxDt}}).solver.rtol,
      integrate::kMinRtol);
}

TEST(SolverBlock, AFixedStepRunTooLongForTheStepLimitIsRefusedByName) {
  const std::string message = refusal({{"method", "rk4"}, {"dt", 1e-7}});
  EXPECT_NE(message.find("solver.dt: duration / dt = 6e+07 steps of rk4"), std::string::npos) << message;
}

}  // namespace
}  // namespace coinroll::scene
