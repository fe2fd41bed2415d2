// The frame loop against its contract: one frame per t_k = k time_scale / fps up to the end of
// the run, each drawn from the dense-output state at that time, the sink finished exactly once,
// and cancellation leaving the sink unfinished.

#include <gtest/gtest.h>

#include <atomic>

#include "physics/observables.h"
#include "pipeline/coin_run.h"
#include "pipeline/framing.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

class RecordingSink final : public video::FrameSink {
 public:
  void push(const image::Image& frame) override { frames.push_back(frame); }
  void finish() override { ++finishes; }
  std::vector<image::Image> frames;
  int finishes = 0;
};

scene::SceneConfig toyScene(double duration, double timeScale) {
  nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
      {"initial", {{"theta", 20}, {"omega_Y", 3.0}, {"omega_Z", 14.0}}},
      {"duration", duration},
      {"render", {{"width", 96}, {"height", 64}, {"fps", 10}, {"msaa", 1}, {"time_scale", timeScale}}},
  };
  const std::vector<std::string_view> methods = {"dop853"};
  return scene::parseScene(doc, "test", {.solverMethods = methods});
}

TEST(FrameCount, CoversTheClipIncludingBothEnds) {
  EXPECT_EQ(pipeline::frameCount(2.0, 1.0, 30), 61);   // 2 s at 30 fps: t = 0, 1/30, ..., 2
  EXPECT_EQ(pipeline::frameCount(5.0, 1.0, 30), 151);  // 5 * 30 = 149.99999... in binary
  EXPECT_EQ(pipeline::frameCount(1.0, 0.5, 24), 49);   // slowed down twice: 2 s of video
  EXPECT_EQ(pipeline::frameCount(0.01, 1.0, 30), 1);
}

TEST(FrameTimes, RemapHoldsTheOnScreenSpinRateAtTheLimit) {
  scene::SceneConfig scene = toyScene(1.0, 0.5);
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  const std::vector<double> constant = pipeline::frameTimes(scene, simulation, 1.0);
  ASSERT_EQ(constant.size(), 21u);
  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin, .limit = 1000};  // far above the coin's ~15 rad/s: no effect
  const std::vector<double> unchanged = pipeline::frameTimes(scene, simulation, 1.0);
  ASSERT_EQ(unchanged.size(), constant.size());
  for (std::size_t k = 0; k < constant.size(); ++k) EXPECT_NEAR(unchanged[k], constant[k], 1e-14);

  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin, .limit = 5};  // the coin spins at about 15 rad/s: about three times slower
  const std::vector<double> remapped = pipeline::frameTimes(scene, simulation, 1.0);
  EXPECT_GT(remapped.size(), 2.5 * constant.size());
  pipeline::CoinRun trajectory(simulation);
  for (std::size_t k = 0; k + 1 < remapped.size(); ++k) {
    const double spin = std::abs(physics::spinRate(*trajectory.stateAt(remapped[k])));
    ASSERT_GT(spin, 5);
    // Simulated radians of spin per video second = |psi-dot| dt fps = S time_scale.
    EXPECT_NEAR(spin * (remapped[k + 1] - remapped[k]) * scene.render.fps, 5 * 0.5, 1e-12) << "frame " << k;
  }
}

TEST(RenderVideo, PushesOneDistinctFramePerFrameTimeAndFinishesOnce) {
  const scene::SceneConfig scene = toyScene(1.0, 0.5);
  RecordingSink sink;
  long progressCalls = 0;
  const pipeline::VideoRunResult result =
      pipeline::renderVideo(scene, sink, {.onFrame = [&](const pipeline::FrameProgress& p) {
                              ++progressCalls;
                              EXPECT_EQ(p.total, 21);
                            }});
  EXPECT_EQ(result.frames, 21);  // 1 s simulated at half speed = 2 s at 10 fps, both ends
  ASSERT_EQ(sink.frames.size(), 21u);
  EXPECT_EQ(progressCalls, 21);
  EXPECT_EQ(sink.finishes, 1);
  for (std::size_t k = 1; k < sink.frames.size(); ++k) {
    EXPECT_NE(sink.frames[k].rgba, sink.frames[k - 1].rgba) << "frame " << k << " repeats the one before";
  }
  EXPECT_FALSE(result.stopDescription);
}

TEST(RenderVideo, AFrameDependsOnlyOnItsTimeNotOnTheFrameRate) {
  // The loop samples the dense output at t_k rather than stepping at the frame rate, and the
  // trace is sampled on its own fixed grid: so every second frame at 10 fps must be the very
  // frame at 5 fps for the same time (pose, trace, overlay), byte for byte.
  scene::SceneConfig at10 = toyScene(1.0, 1.0), at5 = toyScene(1.0, 1.0);
  at5.render.fps = 5;
  RecordingSink ten, five;
  pipeline::renderVideo(at10, ten);
  pipeline::renderVideo(at5, five);
  ASSERT_EQ(ten.frames.size(), 11u);
  ASSERT_EQ(five.frames.size(), 6u);
  // The HUD shows the same t; the trace holds the same points up to t; the pose is the same.
  for (std::size_t k = 0; k < five.frames.size(); ++k) EXPECT_EQ(five.frames[k].rgba, ten.frames[2 * k].rgba) << "frame " << k;
}

TEST(RenderVideo, CancellationLeavesTheSinkUnfinished) {
  const scene::SceneConfig scene = toyScene(1.0, 1.0);
  RecordingSink sink;
  std::atomic<bool> cancel{false};
  EXPECT_THROW(pipeline::renderVideo(scene, sink,
                                     {.onFrame = [&](const pipeline::FrameProgress& p) {
                                        if (p.frame == 3) cancel = true;
                                      },
                                      .cancel = &cancel}),
               pipeline::Cancelled);
  EXPECT_EQ(sink.frames.size(), 3u);
  EXPECT_EQ(sink.finishes, 0);
}

}  // namespace
