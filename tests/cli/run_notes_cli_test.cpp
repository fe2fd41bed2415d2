// What `coinroll simulate` says on stderr about a run's course (docs/contract.md §6): where it
// starts off the rolling constraint, its switches, impacts and warnings in the order the coin met
// them.

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using coinroll::testing::runCoinroll;
using coinroll::testing::RunResult;

class RunNotesCliTest : public coinroll::testing::ScratchDirTest {
 protected:
  RunResult simulate(const std::string& json) const {
    const fs::path scene = dir_ / "scene.json";
    std::ofstream(scene) << json;
    return runCoinroll("simulate " + scene.string() + " --csv " + (dir_ / "run.csv").string());
  }
};

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST_F(RunNotesCliTest, ASkidStatesThatItSlidesFromTimeZeroAsTheLaterSwitchesAreStated) {
  // An upright disk launched skidding at 1 m/s: slides from the start, rolls from v0 / (3 mu g).
  const RunResult r = simulate(R"({"coin": {"radius": 0.0375, "mass": 0.4}, "friction": 0.3, "sliding": true,
    "initial": {"theta": 0, "v_x": 1.0}, "duration": 0.3})");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::vector<std::string> lines = linesOf(r.output);
  ASSERT_GE(lines.size(), 3u) << r.output;
  EXPECT_EQ(lines[0], "coinroll: slides at t = 0.000000000 s") << r.output;
  EXPECT_EQ(lines[1], "coinroll: rolls at t = 0.113263110 s") << r.output;
}

TEST_F(RunNotesCliTest, AStartBeyondTheStaticConeStatesThatItSlidesFromTimeZero) {
  // Let go at rest at 30 degrees: rolling would need F/N of about 0.3 at once, above the cone of 0.05.
  const RunResult r = simulate(R"({"coin": {"radius": 0.0375, "mass": 0.4}, "friction": 0.05, "sliding": true,
    "initial": {"theta": 30}, "duration": 0.05})");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(linesOf(r.output).at(0), "coinroll: slides at t = 0.000000000 s") << r.output;
  // A start that rolls says nothing about it, as before.
  const RunResult rolling = simulate(R"({"coin": {"radius": 0.0375, "mass": 0.4}, "friction": 0.9, "sliding": true,
    "initial": {"theta": 10, "omega_Z": 12}, "duration": 0.05})");
  ASSERT_EQ(rolling.exitCode, 0) << rolling.output;
  EXPECT_EQ(rolling.output.find("slides at t = 0.000000000 s"), std::string::npos) << rolling.output;
}

TEST_F(RunNotesCliTest, TheTossesSwitchesAndImpactsComeInSimulatedTimeOrder) {
  // The toss bounces (impacts from 0.395 s), then rolls and slides (from 1.67 s): every timed note's
  // t is at least the one before, and each kind of note is still there.
  const RunResult r =
      runCoinroll("simulate " + std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json --csv /dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::regex timed(R"(^coinroll: (slides|rolls|impact|warning:.*) at t = ([0-9.]+))");
  double last = -1;
  int impacts = 0, switches = 0;
  for (const std::string& line : linesOf(r.output)) {
    std::smatch m;
    if (line.starts_with("coinroll: stopped early:")) break;
    if (!std::regex_search(line, m, timed)) continue;
    const double t = std::stod(m[2].str());
    EXPECT_GE(t, last) << line << "\n" << r.output;
    last = t;
    (m[1].str() == "impact" ? impacts : switches) += 1;
  }
  EXPECT_GE(impacts, 5) << r.output;
  EXPECT_GE(switches, 5) << r.output;
}

TEST_F(RunNotesCliTest, AnIdealSceneIsToldTheFrictionItsRollingNeeded) {
  // No `friction`: nothing watches the cone, so the summary says the largest |F|/N (here a coin let go
  // at rest at 30 degrees, 0.05 s: the ratio grows as it falls), and the friction that scene takes
  // reproduces it: with mu just below it the same run slips, just above it it does not.
  const std::string ideal = R"({"coin": {"radius": 0.0375, "mass": 0.4}, "initial": {"theta": 30}, "duration": 0.05)";
  const RunResult r = simulate(ideal + "}");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::regex needed(R"(no friction cone \(the scene has no `friction`\): )"
                          R"(rolling needed \|F\|/N up to ([0-9.]+), at t = ([0-9.]+) s)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, needed)) << r.output;
  const double ratio = std::stod(m[1].str());
  EXPECT_GT(ratio, 0.1) << r.output;
  const RunResult below = simulate(ideal + ", \"friction\": " + std::to_string(0.999 * ratio) + "}");
  EXPECT_NE(below.output.find("stopped early: slip at t = "), std::string::npos) << below.output;
  const RunResult above = simulate(ideal + ", \"friction\": " + std::to_string(1.001 * ratio) + "}");
  EXPECT_EQ(above.output.find("slip at t = "), std::string::npos) << above.output;
  EXPECT_EQ(above.output.find("no friction cone"), std::string::npos) << above.output;
  // A coin spinning in place needs none.
  const RunResult spin =
      runCoinroll("simulate " + std::string(COINROLL_SOURCE_DIR) + "/examples/spin_in_place.json --csv /dev/null");
  EXPECT_NE(spin.output.find("rolling needed no friction"), std::string::npos) << spin.output;
}

}  // namespace
