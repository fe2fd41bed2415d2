// The run every door shares: what it refuses before any row, what it hands the sink, and how it
// reports the end, against the pieces it is made of (sampleTrajectory, eventName).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "physics/validity.h"
#include "pipeline/scene_run.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

pipeline::SceneRunRequest requestFor(double sampleDt, std::string_view sampleDtName) {
  pipeline::SceneRunRequest request;
  request.sampleDt = sampleDt;
  request.sampleDtName = sampleDtName;
  return request;
}

scene::SceneConfig defaultScene() { return scene::parseScene(scene::builtInDefaultScene(), "built-in default scene"); }

// Counts what the run hands its sink.
struct CountingSink {
  int begins = 0;
  long rows = 0;
  long rowsBeforeBegin = 0;
  pipeline::RunStart start;

  pipeline::RowSink sink() {
    const auto begin = [this](const pipeline::RunStart& started) {
      ++begins;
      start = started;
    };
    const auto row = [this](std::span<const double>) { ++(begins == 0 ? rowsBeforeBegin : rows); };
    return {.begin = begin, .row = row};
  }
};

// The refusal's message, or "" when the run went ahead.
std::string refusal(const scene::SceneConfig& scene, const pipeline::SceneRunRequest& request, CountingSink& counts) {
  try {
    pipeline::simulateScene(scene, request, counts.sink());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(SimulateScene, RefusesABadSampleStepByTheDoorsNameBeforeAnyRow) {
  for (const double sampleDt :
       {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    CountingSink counts;
    const std::string message = refusal(defaultScene(), requestFor(sampleDt, "sample_dt"), counts);
    EXPECT_TRUE(message.starts_with("sample_dt: must be a finite number > 0 s")) << message;
    EXPECT_EQ(counts.begins, 0);
  }
}

TEST(SimulateScene, RefusesTooManyRowsInTheDoorsWordsBeforeAnyRow) {
  CountingSink counts;
  std::size_t costColumns = 0;
  pipeline::SceneRunRequest request = requestFor(1e-3, "--sample-dt");
  request.maxRows = 10;
  request.maxRowsOption = "--max-rows";
  request.rowsCost = [&costColumns](double, std::size_t columns) {
    costColumns = columns;
    return std::string("a lot");
  };
  const scene::SceneConfig scene = defaultScene();
  const std::string message = refusal(scene, request, counts);
  EXPECT_NE(message.find("--sample-dt 0.001"), std::string::npos) << message;
  EXPECT_NE(message.find("(a lot)"), std::string::npos) << message;
  EXPECT_NE(message.find("or the limit with --max-rows"), std::string::npos) << message;
  EXPECT_EQ(counts.begins, 0);
  // The cost is told the columns the rows would have had.
  CountingSink run;
  const pipeline::SceneTable table = pipeline::simulateScene(scene, requestFor(0.1, "S"), run.sink());
  EXPECT_EQ(costColumns, table.start.columns.size());
}

TEST(SimulateScene, BeginsOnceBeforeTheRowsAndEndsAtTheDurationByName) {
  CountingSink counts;
  const scene::SceneConfig scene = defaultScene();
  const pipeline::SceneTable table = pipeline::simulateScene(scene, requestFor(0.05, "S"), counts.sink());
  ASSERT_FALSE(table.run.stoppedBy) << "the built-in scene rolls to its duration";
  EXPECT_EQ(counts.begins, 1);
  EXPECT_EQ(counts.rowsBeforeBegin, 0);
  EXPECT_EQ(counts.rows, table.run.rows);
  EXPECT_EQ(counts.start.expectedRows, table.run.rows);
  EXPECT_EQ(counts.start.columns, table.start.columns);
  EXPECT_EQ(table.end.event, "duration");
  EXPECT_EQ(table.end.time, scene.duration);
  EXPECT_TRUE(table.end.description.empty());
  EXPECT_TRUE(table.marks.empty());
  ASSERT_FALSE(table.report.empty());
  EXPECT_TRUE(table.report.back().starts_with("coinroll: " + std::to_string(table.run.rows) + " rows"));
}

TEST(SimulateScene, AnEarlyStopIsTheEndAndTheLastMarkAfterTheSwitchesInTimeOrder) {
  const scene::SceneConfig scene =
      scene::loadScene(std::string(COINROLL_SOURCE_DIR) + "/examples/skid_and_spin.json", {});
  CountingSink counts;
  const pipeline::SceneTable table = pipeline::simulateScene(scene, requestFor(0.01, "S"), counts.sink());
  ASSERT_TRUE(table.run.stoppedBy) << "skid_and_spin ends face-down";
  const pipeline::RunEvent& stop = *table.run.stoppedBy;
  EXPECT_EQ(table.end.event, physics::eventName(stop.event));
  EXPECT_EQ(table.end.time, stop.t);
  EXPECT_EQ(table.end.description, pipeline::describeStop(stop));
  ASSERT_EQ(table.marks.size(), table.run.switches.size() + table.run.warnings.size() + 1);
  EXPECT_EQ(table.marks.back().kind, "stop");
  EXPECT_EQ(table.marks.back().name, table.end.event);
  for (std::size_t i = 1; i + 1 < table.marks.size(); ++i) EXPECT_LE(table.marks[i - 1].time, table.marks[i].time);
  const std::string stopLine = "coinroll: stopped early: " + table.end.description;
  EXPECT_NE(std::find(table.report.begin(), table.report.end(), stopLine), table.report.end());
}

}  // namespace
