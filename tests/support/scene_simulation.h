#pragma once
// Scenes written in a test as JSON, turned into the Simulation the program would run: the loader's
// rules and the simulation's set-up are the program's own, so a test's scene is one a user could give.

#include <nlohmann/json.hpp>

#include "pipeline/simulation.h"
#include "scene/scene_loader.h"

namespace coinroll::testing {

inline pipeline::Simulation simulationOf(const nlohmann::json& scene) {
  return pipeline::buildSimulation(scene::parseScene(scene, "test"));
}

// A solver block two decades tighter than the default, for comparisons with closed forms.
inline const nlohmann::json kTightSolver = {{"rtol", 1e-12}, {"atol", 1e-14}};

}  // namespace coinroll::testing
