// The overlay's contact rate against the motion it names: a precessing coin's Omega in Hz, and no
// number for a coin that rocks through flat (whose phi-dot is a kHz whip of its heading).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "pipeline/snapshot.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

std::string contactLine(const nlohmann::json& doc, double time) {
  const scene::SceneConfig scene = scene::parseScene(doc, "test");
  const pipeline::Simulation sim = pipeline::buildSimulation(scene);
  pipeline::FixedFrameTimes at({time});
  const pipeline::RunRecord record = pipeline::recordRun(sim, at);
  pipeline::SnapshotMaker maker(scene, sim.model, record);
  for (const std::string& line : maker.makeSnapshot(record.frames.at(0)).hudLines) {
    if (line.starts_with("contact")) return line;
  }
  return {};
}

}  // namespace

TEST(Overlay, AnEulersDiskSpinningInPlaceShowsItsContactRateInHertz) {
  // A thin disk spinning in place at theta from vertical has I_X omega_Y^2 = M g a cos(theta)
  // (docs/derivations.md), so Omega = omega_Y / cos(theta) = sqrt(4 g / (a cos(theta))): the rate shown.
  const double a = 0.0375, g = 9.81, theta = 75 * std::numbers::pi / 180;
  const nlohmann::json doc = {{"coin", {{"radius", a}, {"mass", 0.4}}},
                              {"initial", {{"steady", "spin-in-place"}, {"theta", 75}}},
                              {"duration", 0.5}};
  const double omega = std::sqrt(4 * g / (a * std::cos(theta)));
  EXPECT_EQ(contactLine(doc, 0.25), fmt::format("contact  {:9.2f} Hz round the floor", omega / (2 * std::numbers::pi)));
}

TEST(Overlay, ACoinRockingThroughFlatShowsNoContactRate) {
  // falling_flat: released at 60 deg without spin, it rocks between 60 and about 89 deg; near flat
  // its heading whips round at hundreds of Hz while nothing circles the floor.
  const nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
                              {"initial", {{"theta", 60}, {"omega_Z", 0.1}}},
                              {"duration", 0.2},
                              {"solver", {{"formulation", "quaternion"}}}};
  for (const double t : {0.04, 0.08, 0.12, 0.16}) {
    EXPECT_EQ(contactLine(doc, t), "contact         -- rocking, not going round") << "t = " << t;
  }
}
