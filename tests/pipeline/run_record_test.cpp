// The one pass over a run that `render` and `still` draw from (pipeline/run_record.h): it is the run
// integrated once, each frame is what an independent run gives at that frame's time, and its frames
// stay compact however long the clip.

#include <gtest/gtest.h>

#include <optional>
#include <string_view>
#include <vector>

#include "pipeline/coin_run.h"
#include "pipeline/motion_survey.h"
#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

scene::SceneConfig sceneOf(nlohmann::json doc) {
  doc["render"]["fps"] = 24;
  return scene::parseScene(doc, "test");
}

// A precessing coin in the Euler angles; the same in quaternions with a time remap; a coin that
// stops near flat early (the last frame at the event); a skid that slides, then rolls.
std::vector<scene::SceneConfig> scenes() {
  const nlohmann::json coin = {{"radius", 0.0375}, {"mass", 0.4}};
  std::vector<scene::SceneConfig> all = {
      sceneOf({{"coin", coin}, {"initial", {{"theta", 20}, {"omega_Y", 3.0}, {"omega_Z", 14.0}}}, {"duration", 1.3}}),
      sceneOf({{"coin", coin},
               {"initial", {{"theta", 20}, {"omega_Y", 3.0}, {"omega_Z", 14.0}}},
               {"duration", 1.0},
               {"solver", {{"formulation", "quaternion"}}},
               {"render", {{"time_remap", {{"spin_rate", 5}}}}}}),
      sceneOf({{"coin", coin}, {"initial", {{"theta", 60}, {"omega_Z", 0.1}}}, {"duration", 1.0}}),
      sceneOf({{"coin", coin},
               {"initial", {{"theta", 0}, {"omega_Z", 20.0}, {"v_x", 0.5}, {"v_z", 0.0}}},
               {"sliding", true},
               {"friction", 0.3},
               {"duration", 0.4}}),
  };
  return all;
}

void expectSameFrame(const pipeline::FrameState& a, const pipeline::FrameState& b, double t) {
  EXPECT_EQ(a.time, b.time) << "t = " << t;
  EXPECT_EQ(a.centre, b.centre) << "t = " << t;
  EXPECT_EQ(a.attitude, b.attitude) << "t = " << t;
  EXPECT_EQ(a.contact, b.contact) << "t = " << t;
  EXPECT_EQ(a.theta, b.theta) << "t = " << t;
  EXPECT_EQ(a.omega_Z, b.omega_Z) << "t = " << t;
  EXPECT_EQ(a.precessionRate, b.precessionRate) << "t = " << t;
  EXPECT_EQ(a.energy, b.energy) << "t = " << t;
  EXPECT_EQ(a.power, b.power) << "t = " << t;
  EXPECT_EQ(a.slipSpeed, b.slipSpeed) << "t = " << t;
  EXPECT_EQ(a.sliding, b.sliding) << "t = " << t;
  EXPECT_EQ(a.axisGoesRound, b.axisGoesRound) << "t = " << t;
}

}  // namespace

TEST(RunRecord, EachFrameIsWhatARunSampledOnlyAtTheFrameTimesGives) {
  for (const scene::SceneConfig& scene : scenes()) {
    const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
    const pipeline::RunRecord record = pipeline::recordFrames(scene, simulation);
    ASSERT_GE(record.frames.size(), 2u);
    pipeline::CoinRun alone(simulation);
    for (const pipeline::FrameState& frame : record.frames) {
      const std::optional<pipeline::RunSample> sample = alone.sampleAt(frame.time);
      ASSERT_TRUE(sample.has_value()) << "t = " << frame.time;
      expectSameFrame(frame, pipeline::frameStateOf(frame.time, *sample), frame.time);
    }
    // The end, an event's or the duration's, as a run asked for it gives it.
    const double end = record.survey.endTime;
    ASSERT_LE(record.frames.back().time, end);
    // Without a remap the frames are those of k time_scale / fps up to the end, an early one too.
    if (!scene.render.timeRemap) {
      EXPECT_EQ(static_cast<long>(record.frames.size()),
                pipeline::frameCount(end, scene.render.timeScale, scene.render.fps));
    }
    const std::optional<pipeline::RunSample> last = alone.sampleAt(end);
    ASSERT_TRUE(last.has_value());
    expectSameFrame(record.end, pipeline::frameStateOf(end, *last), end);
  }
  // The scenes cover a run an event ends early.
  EXPECT_TRUE(pipeline::surveyMotion(pipeline::buildSimulation(scenes()[2])).stoppedBy.has_value());
}

TEST(RunRecord, TheTraceIsTheContactPointEveryTraceIntervalWhileTheRunLasts) {
  for (const scene::SceneConfig& scene : scenes()) {
    const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
    const pipeline::RunRecord record = pipeline::recordFrames(scene, simulation);
    const double dt = pipeline::traceInterval(simulation.duration);
    ASSERT_EQ(record.trace.size(), record.traceSlides.size());
    std::size_t onTheGrid = 0;  // points j with j dt <= the run's end
    while (static_cast<double>(onTheGrid) * dt <= record.survey.endTime) ++onTheGrid;
    EXPECT_EQ(record.trace.size(), onTheGrid);
    pipeline::CoinRun alone(simulation);
    for (std::size_t j = 0; j < record.trace.size(); ++j) {
      const pipeline::FrameState at = pipeline::frameStateOf(0, *alone.sampleAt(static_cast<double>(j) * dt));
      ASSERT_EQ(record.trace[j], at.contact) << "point " << j;
      ASSERT_EQ(record.traceSlides[j], at.sliding) << "point " << j;
    }
  }
}

TEST(RunRecord, OnePassDoesTheStepsOfOneRunToTheEnd) {
  // The frames and the trace are read from one integration: its steps are those of a run taken to
  // its end with nothing sampled on the way (the steps do not depend on the samples asked for).
  for (const scene::SceneConfig& scene : scenes()) {
    const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
    const pipeline::RunRecord record = pipeline::recordFrames(scene, simulation);
    pipeline::CoinRun plain(simulation);
    plain.sampleAt(record.survey.endTime);
    EXPECT_EQ(record.stats.acceptedSteps, plain.stats().acceptedSteps);
    EXPECT_EQ(record.stats.rejectedSteps, plain.stats().rejectedSteps);
    EXPECT_GT(record.stats.acceptedSteps, 0);
    // The survey alone is the same pass without frames.
    const pipeline::MotionSurvey survey = pipeline::surveyMotion(simulation);
    EXPECT_EQ(survey.lower, record.survey.lower);
    EXPECT_EQ(survey.upper, record.survey.upper);
    EXPECT_EQ(survey.endTime, record.survey.endTime);
  }
}

TEST(RunRecord, AFrameTakesAFixedFewBytesSoTheFrameLimitBoundsMemory) {
  // 112 bytes (video_frames.h): the default limit of 1 000 000 frames is 112 MB of records.
  EXPECT_LE(sizeof(pipeline::FrameState), 112u);
  EXPECT_LE(static_cast<double>(sizeof(pipeline::FrameState)) * pipeline::kDefaultMaxFrames, 112e6);
}
