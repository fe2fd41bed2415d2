// The visual track a page draws from (pipeline/visual_track.h) against `render` itself: each row's
// overlay is the one the renderer draws at that time, the seed's units rescale the same numbers, and
// the clock is the clip render plans.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <regex>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "pipeline/motion_survey.h"
#include "pipeline/run_record.h"
#include "pipeline/scene_run.h"
#include "pipeline/simulation.h"
#include "pipeline/snapshot.h"
#include "pipeline/visual_track.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

scene::SceneConfig example(const std::string& name, std::span<const std::string> overrides = {}) {
  return scene::loadScene(std::string(COINROLL_SOURCE_DIR) + "/examples/" + name + ".json", overrides);
}

// The Euler's disk's first 20 s: dissipation on every line at a fifth of its cost; the whole spin-down,
// the costliest run here (ten times so under the sanitizers), is kept for the clock it slows.
const std::vector<std::string> kFirst20s = {"duration=20"};

struct TrackedRun {
  pipeline::VisualTrack track;
  std::vector<double> times;  // s, of the rows
};

TrackedRun tracked(const scene::SceneConfig& scene) {
  std::optional<pipeline::VisualTrackBuilder> builder;
  TrackedRun run;
  pipeline::SceneRunRequest request;
  request.sampleDt = pipeline::traceInterval(scene.duration);
  request.sampleDtName = "sampleDt";
  pipeline::simulateScene(scene, request,
                          {.begin = [&](const pipeline::RunStart& start) { builder.emplace(scene, *start.model); },
                           .row = [](std::span<const double>) {},
                           .sample =
                               [&](double t, const pipeline::RunSample& sample, bool row) {
                                 builder->add(t, sample, row);
                                 if (row) run.times.push_back(t);
                               }});
  run.track = std::move(*builder).finish(nullptr);
  return run;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += (text.empty() ? "" : "\n") + line;
  return text;
}

// The numbers a line prints, in order.
std::vector<double> numbersIn(const std::string& line) {
  static const std::regex number(R"(-?\d+(\.\d+)?(e-?\d+)?)");
  std::vector<double> values;
  for (auto it = std::sregex_iterator(line.begin(), line.end(), number); it != std::sregex_iterator(); ++it)
    values.push_back(std::stod(it->str()));
  return values;
}

}  // namespace

// Rolling (the built-in default), in flight and bouncing (the toss), sliding (skid and spin) and with
// dissipation (the Euler's disk): every overlay line the track holds for a row is what render's
// SnapshotMaker draws at that row's time, from its own pass over the run.
TEST(VisualTrack, EachRowsOverlayIsTheOneRenderDrawsAtThatTime) {
  for (const std::string name : {"steady_circle", "coin_toss", "skid_and_spin", "euler_disk"}) {
    const scene::SceneConfig scene = example(name, name == "euler_disk" ? kFirst20s : std::vector<std::string>{});
    const TrackedRun run = tracked(scene);
    ASSERT_EQ(run.track.overlaySi.size(), run.times.size()) << name;
    std::vector<double> checked;
    for (std::size_t i = 0; i < run.times.size(); i += 37) checked.push_back(run.times[i]);
    const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
    pipeline::FixedFrameTimes at(checked);
    const pipeline::RunRecord record = pipeline::recordRun(simulation, at);
    pipeline::SnapshotMaker maker(scene, simulation.model, record);
    ASSERT_EQ(record.frames.size(), checked.size()) << name;
    for (std::size_t k = 0; k < checked.size(); ++k) {
      EXPECT_EQ(run.track.overlaySi[37 * k], joined(maker.makeSnapshot(record.frames[k]).hudLines))
          << name << " at t = " << checked[k];
    }
  }
}

// The seed's units (M = a = g = 1): the same moment's numbers divided by the units' sizes, to the
// digits printed; the tilt in degrees and the impacts unchanged.
TEST(VisualTrack, TheSeedsOverlayIsTheSameMomentInTheSeedsUnits) {
  for (const std::string name : {"steady_circle", "euler_disk"}) {
    const scene::SceneConfig scene = example(name, name == "euler_disk" ? kFirst20s : std::vector<std::string>{});
    const TrackedRun run = tracked(scene);
    const physics::CoinModel model = pipeline::buildSimulation(scene).model;
    const double time = std::sqrt(model.a / model.g), rate = 1 / time, energy = model.M * model.g * model.a;
    // Hz in SI, radians per unit of time in the seed's; the SI line rounds to 0.005 Hz.
    const double perHertz = 2 * std::numbers::pi / rate, slack = 0.5e-3 + 0.005 * perHertz;
    for (std::size_t i = 0; i < run.times.size(); i += 101) {
      std::vector<std::string> si, seed;
      std::istringstream siText(run.track.overlaySi[i]), seedText(run.track.overlaySeed[i]);
      for (std::string line; std::getline(siText, line);) si.push_back(line);
      for (std::string line; std::getline(seedText, line);) seed.push_back(line);
      ASSERT_EQ(si.size(), seed.size()) << name << " row " << i;
      EXPECT_NEAR(numbersIn(seed[0]).at(0), numbersIn(si[0]).at(0) / time, 0.5e-3 + 0.5e-3 / time) << seed[0];
      EXPECT_EQ(seed[1], si[1]);  // the tilt, in degrees in either
      if (seed[2].find("round the floor") != std::string::npos) {
        EXPECT_NEAR(numbersIn(seed[2]).at(0), numbersIn(si[2]).at(0) * perHertz, slack) << seed[2] << " | " << si[2];
      }
      EXPECT_NEAR(numbersIn(seed[3]).at(0), numbersIn(si[3]).at(0) * perHertz, slack) << seed[3] << " | " << si[3];
      EXPECT_NEAR(numbersIn(seed[4]).at(0), numbersIn(si[4]).at(0) / energy, 0.5e-5 + 0.5e-5 / energy) << seed[4];
      EXPECT_TRUE(seed[0].ends_with(" √(a/g)") && seed[4].ends_with(" Mga")) << seed[0] << " | " << seed[4];
    }
  }
}

// The page plays frame k at k / fps as the video does: the track's clock is render's plan, frame for
// frame, in a clip slowed by the spin (the Euler's disk) and by flight and impacts (the toss).
TEST(VisualTrack, ItsClockIsTheClipRenderPlans) {
  for (const std::string name : {"euler_disk", "coin_toss", "steady_circle"}) {
    const scene::SceneConfig scene = example(name);
    const pipeline::ClipPlan plan = pipeline::planClip(scene);
    const pipeline::VisualTrack track = tracked(scene).track;
    EXPECT_EQ(track.clock.times, plan.times) << name;
    EXPECT_EQ(track.clock.playbackRates, plan.playbackRates) << name;
    EXPECT_EQ(track.clock.fps, scene.render.fps) << name;
  }
}
