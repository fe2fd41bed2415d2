// The frame loop against its contract: one frame per t_k = k time_scale / fps up to the end of
// the run, each drawn from the dense-output state at that time, the sink finished exactly once,
// and cancellation leaving the sink unfinished.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "physics/observables.h"
#include "pipeline/coin_run.h"
#include "pipeline/coin_sound.h"
#include "pipeline/motion_survey.h"
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

// The frame times the one pass over the run chose.
std::vector<double> frameTimes(const scene::SceneConfig& scene, const pipeline::Simulation& simulation) {
  std::vector<double> times;
  for (const pipeline::FrameState& frame : pipeline::recordFrames(scene, simulation).frames)
    times.push_back(frame.time);
  return times;
}

scene::SceneConfig toyScene(double duration, double timeScale) {
  nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
      {"initial", {{"theta", 20}, {"omega_Y", 3.0}, {"omega_Z", 14.0}}},
      {"duration", duration},
      {"render", {{"width", 96}, {"height", 64}, {"fps", 10}, {"msaa", 1}, {"time_scale", timeScale}}},
  };
  return scene::parseScene(doc, "test");
}

TEST(FrameCount, CoversTheClipIncludingBothEnds) {
  EXPECT_EQ(pipeline::frameCount(2.0, 1.0, 30), 61);    // 2 s at 30 fps: t = 0, 1/30, ..., 2
  EXPECT_EQ(pipeline::frameCount(0.29, 1.0, 100), 30);  // 0.29 * 100 = 28.999999999999996 in binary
  EXPECT_EQ(pipeline::frameCount(0.3, 0.1, 10), 31);    // 0.3 / 0.1 = 2.9999999999999996: 3 s of video
  EXPECT_EQ(pipeline::frameCount(1.0, 0.5, 24), 49);    // slowed down twice: 2 s of video
  EXPECT_EQ(pipeline::frameCount(0.01, 1.0, 30), 1);
}

// floor(d / ts * fps) + 1 for a duration d = dNum / dDen s and a time scale ts = tsNum / tsDen, in
// integers: the count the decimal numbers a scene file holds ask for, free of binary rounding.
long exactFrameCount(long dNum, long dDen, long tsNum, long tsDen, long fps) {
  return dNum * tsDen * fps / (dDen * tsNum) + 1;
}

TEST(FrameCount, MatchesExactRationalArithmeticWhereTheProductRoundsBelowAWholeNumber) {
  // Every duration 0.01 .. 30 s in steps of 0.01 s against common time scales and frame rates. In
  // hundreds of these the double d / ts * fps lands just below the whole number it stands for
  // (0.29 s at 100 fps is 28.999999999999996): the rounding nudge must restore the frame.
  struct Ratio {
    long num, den;
  };
  int roundedBelow = 0, failures = 0;
  for (long n = 1; n <= 3000; ++n) {
    for (const Ratio ts : {Ratio{1, 1}, Ratio{1, 2}, Ratio{1, 4}, Ratio{1, 10}, Ratio{3, 10}, Ratio{2, 1}}) {
      for (const long fps : {7, 10, 24, 25, 30, 60, 100, 120}) {
        const double d = static_cast<double>(n) / 100,
                     timeScale = static_cast<double>(ts.num) / static_cast<double>(ts.den);
        const long expected = exactFrameCount(n, 100, ts.num, ts.den, fps);
        const long actual = pipeline::frameCount(d, timeScale, static_cast<int>(fps));
        if (actual != expected && ++failures <= 10) {
          ADD_FAILURE() << "frameCount(" << n << " / 100 s, time scale " << ts.num << "/" << ts.den << ", " << fps
                        << " fps) = " << actual << ", exactly " << expected;
        }
        const bool whole = n * ts.den * fps % (100 * ts.num) == 0;
        if (whole && d / timeScale * static_cast<double>(fps) < static_cast<double>(expected - 1)) ++roundedBelow;
      }
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(roundedBelow, 100);  // the cases the nudge exists for are really among them
}

TEST(FrameCount, LongClipsWhoseProductFallsShortByMoreThanAnAbsoluteNudge) {
  // 15.6 h simulated at time scale 0.1 and 60 fps: 3.4e7 frames (past --max-frames' default, but
  // allowed with it). There d / ts * fps may fall a whole ulp (7.5e-9) short of its whole number,
  // where adding any fixed 1e-9 rounds straight back: only a relative nudge restores the frame.
  int beyondAnAbsoluteNudge = 0, failures = 0;
  for (long n = 5'600'000; n < 5'604'000; ++n) {  // d = n / 100 s
    const double d = static_cast<double>(n) / 100, x = d / 0.1 * 60;
    const long expected = exactFrameCount(n, 100, 1, 10, 60);
    const long actual = pipeline::frameCount(d, 0.1, 60);
    if (actual != expected && ++failures <= 10) {
      ADD_FAILURE() << "frameCount(" << n << " / 100 s, time scale 0.1, 60 fps) = " << actual << ", exactly "
                    << expected;
    }
    if (x + 1e-9 < static_cast<double>(expected - 1)) ++beyondAnAbsoluteNudge;
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(beyondAnAbsoluteNudge, 100);  // such cases are really among them
}

TEST(FrameTimes, RemapHoldsTheOnScreenSpinRateAtTheLimit) {
  scene::SceneConfig scene = toyScene(1.0, 0.5);
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  const std::vector<double> constant = frameTimes(scene, simulation);
  ASSERT_EQ(constant.size(), 21u);
  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin,
                                            .limit = 1000};  // far above the coin's ~15 rad/s: no effect
  const std::vector<double> unchanged = frameTimes(scene, simulation);
  ASSERT_EQ(unchanged.size(), constant.size());
  for (std::size_t k = 0; k < constant.size(); ++k) EXPECT_NEAR(unchanged[k], constant[k], 1e-14);

  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin,
                                            .limit = 5};  // the coin spins at about 15 rad/s: about three times slower
  const std::vector<double> remapped = frameTimes(scene, simulation);
  EXPECT_GT(remapped.size(), 2.5 * constant.size());
  pipeline::CoinRun trajectory(simulation);
  for (std::size_t k = 0; k + 1 < remapped.size(); ++k) {
    const double spin = std::abs(physics::spinRate(*trajectory.stateAt(remapped[k])));
    ASSERT_GT(spin, 5);
    // Simulated radians of spin per video second = |psi-dot| dt fps = S time_scale.
    EXPECT_NEAR(spin * (remapped[k + 1] - remapped[k]) * scene.render.fps, 5 * 0.5, 1e-12) << "frame " << k;
  }
}

TEST(FrameTimes, RemapWithGrowthShowsTheRateGrowingAsItsPowerOfTheRealOne) {
  scene::SceneConfig scene = toyScene(1.0, 0.5);
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin, .limit = 2, .growth = 0.5};
  const std::vector<double> remapped = frameTimes(scene, simulation);
  pipeline::CoinRun trajectory(simulation);
  for (std::size_t k = 0; k + 1 < remapped.size(); ++k) {
    const double spin = std::abs(physics::spinRate(*trajectory.stateAt(remapped[k])));
    ASSERT_GT(spin, 2);
    // On screen, time_scale S (spin / S)^(1/2) rad per video second: about 2.7 for ~15 rad/s, far
    // below the quarter turn per frame (15.7 at 10 fps).
    EXPECT_NEAR(spin * (remapped[k + 1] - remapped[k]) * scene.render.fps, 0.5 * 2 * std::sqrt(spin / 2), 1e-12)
        << "frame " << k;
  }
}

TEST(PlaybackRate, TheVisibleRateRisesWithTheRealOneUpToAQuarterTurnPerFrame) {
  scene::RenderSpec render;
  render.fps = 60;
  render.timeScale = 2;
  render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Precession, .limit = 10, .growth = 0.5};
  const auto visible = [&](double rate) { return rate * pipeline::playbackRate(render, rate); };
  EXPECT_DOUBLE_EQ(pipeline::playbackRate(render, 5), 2);  // below the limit: time_scale
  EXPECT_DOUBLE_EQ(visible(10), 20);
  EXPECT_NEAR(visible(40), 40, 1e-12);  // 2 x 10 x (40 / 10)^(1/2)
  EXPECT_NEAR(visible(90), 60, 1e-12);
  const double quarterTurnPerFrame = std::numbers::pi / 2 * 60;
  EXPECT_NEAR(visible(1e6), quarterTurnPerFrame, 1e-9);
  for (double rate = 10; rate < 1e4; rate *= 1.1) EXPECT_LE(visible(rate), visible(rate * 1.1) + 1e-12) << rate;

  render.timeRemap->growth = 0;  // the original rule: held at time_scale S
  EXPECT_NEAR(visible(40), 20, 1e-12);
  EXPECT_NEAR(visible(1e6), 20, 1e-9);
  // A held rate above the quarter turn stays held: growth never makes a clip faster.
  render.timeRemap->limit = 100;
  render.timeRemap->growth = 0.5;
  EXPECT_NEAR(visible(1e4), 200, 1e-9);
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
  for (std::size_t k = 0; k < five.frames.size(); ++k)
    EXPECT_EQ(five.frames[k].rgba, ten.frames[2 * k].rgba) << "frame " << k;
}

// The frames a window writes (--from/--to), against the full render's: the same frames, byte for
// byte, for exactly the times in the window; also where a time remap makes the steps uneven.
void expectWindowIsASliceOfTheFullRender(const scene::SceneConfig& scene, double from, double to) {
  RecordingSink full, window;
  pipeline::renderVideo(scene, full);
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  const std::vector<double> times = frameTimes(scene, simulation);
  ASSERT_EQ(times.size(), full.frames.size());
  const pipeline::VideoRunResult result = pipeline::renderVideo(scene, window, {.window = {.from = from, .to = to}});
  std::vector<std::size_t> inside;
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (times[k] >= from - 1e-9 && times[k] <= to + 1e-9) inside.push_back(k);
  }
  ASSERT_FALSE(inside.empty());
  ASSERT_EQ(window.frames.size(), inside.size());
  EXPECT_EQ(result.frames, static_cast<long>(inside.size()));
  EXPECT_EQ(window.finishes, 1);
  for (std::size_t i = 0; i < inside.size(); ++i) {
    EXPECT_EQ(window.frames[i].rgba, full.frames[inside[i]].rgba)
        << "window frame " << i << " (t = " << times[inside[i]] << " s)";
  }
}

TEST(RenderVideo, AWindowWritesTheFullRendersFramesWithinIt) {
  expectWindowIsASliceOfTheFullRender(toyScene(1.0, 1.0), 0.5, 1.0);  // 0.5 .. 1.0 s at 10 fps: 6 frames
  expectWindowIsASliceOfTheFullRender(toyScene(1.0, 0.5), 0.3, 0.6);  // half speed: frames every 0.05 s
}

TEST(RenderVideo, AWindowFollowsSimulatedTimeUnderATimeRemap) {
  scene::SceneConfig scene = toyScene(1.0, 1.0);
  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin, .limit = 5};  // about 3x slower
  expectWindowIsASliceOfTheFullRender(scene, 0.4, 0.7);
}

// The plan (render --plan) is the clip renderVideo draws: the same frames at the same simulated times
// and playback rates, under a time remap too.
TEST(PlanClip, IsTheClipRenderVideoDraws) {
  scene::SceneConfig scene = toyScene(1.0, 1.0);
  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin, .limit = 5, .growth = 0.5};
  std::vector<pipeline::FrameTiming> drawn;
  RecordingSink sink;
  pipeline::renderVideo(scene, sink, {.onFrameTiming = [&](const pipeline::FrameTiming& f) { drawn.push_back(f); }});
  const pipeline::ClipPlan plan = pipeline::planClip(scene);
  ASSERT_EQ(plan.frames(), static_cast<long>(drawn.size()));
  EXPECT_EQ(plan.videoSeconds(), static_cast<double>(drawn.size()) / scene.render.fps);
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    EXPECT_EQ(plan.times[k], drawn[k].simulatedTime) << "frame " << k;
    EXPECT_EQ(plan.playbackRates[k], drawn[k].playbackRate) << "frame " << k;
  }
}

// A window by video time keeps the frames that play in it, k / fps in [from, to]; --last L the
// frames of the clip's last L s; a render with it draws the frames of the simulated window between them.
TEST(FramesIn, AVideoWindowKeepsTheFramesThatPlayInIt) {
  scene::SceneConfig scene = toyScene(1.0, 1.0);
  scene.render.timeRemap = scene::TimeRemap{.rate = scene::TimeRemap::Rate::Spin, .limit = 5};  // about 3x slower
  const pipeline::ClipPlan plan = pipeline::planClip(scene);
  ASSERT_GT(plan.frames(), 25);
  using Clock = pipeline::TimeWindow::Clock;
  const pipeline::FrameRange video = pipeline::framesIn(plan, {.from = 0.5, .to = 1.2, .clock = Clock::Video});
  EXPECT_EQ(video.first, 5);  // 10 fps
  EXPECT_EQ(video.last, 12);
  const pipeline::FrameRange last = pipeline::framesIn(plan, {.last = 0.8});
  EXPECT_EQ(last.first, plan.frames() - 8);
  EXPECT_EQ(last.last, plan.frames() - 1);
  RecordingSink byVideo, bySimulated;
  pipeline::renderVideo(scene, byVideo, {.window = {.from = 0.5, .to = 1.2, .clock = Clock::Video}});
  pipeline::renderVideo(scene, bySimulated, {.window = {.from = plan.times[5], .to = plan.times[12]}});
  ASSERT_EQ(byVideo.frames.size(), 8u);
  ASSERT_EQ(bySimulated.frames.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(byVideo.frames[i].rgba, bySimulated.frames[i].rgba) << "frame " << i;
  EXPECT_THROW(pipeline::framesIn(plan, {.from = 100, .clock = Clock::Video}), std::invalid_argument);
}

// render --inset: every frame gains the plot in its lower half and nothing above, and the plot's
// marker moves with the frame.
TEST(RenderVideo, AnInsetChangesOnlyTheLowerHalfAndFollowsTheFrame) {
  scene::SceneConfig scene = toyScene(1.0, 1.0);
  scene.render.picture.width = 320;  // the inset's labels need the room of a real picture
  scene.render.picture.height = 180;
  RecordingSink plain, inset;
  pipeline::renderVideo(scene, plain);
  pipeline::renderVideo(scene, inset, {.inset = true});
  ASSERT_EQ(plain.frames.size(), inset.frames.size());
  ASSERT_GT(inset.frames.size(), 2u);
  // Which pixels the inset changed in frame k.
  const auto insetPixels = [&](std::size_t k) {
    std::vector<bool> changed;
    const image::Image &a = plain.frames[k], &b = inset.frames[k];
    for (int y = 0; y < a.height; ++y) {
      for (int x = 0; x < a.width; ++x) changed.push_back(!std::equal(a.pixel(x, y), a.pixel(x, y) + 4, b.pixel(x, y)));
    }
    return changed;
  };
  const std::size_t upperHalf = 320 * 90;  // pixels
  for (std::size_t k = 0; k < inset.frames.size(); ++k) {
    const std::vector<bool> changed = insetPixels(k);
    EXPECT_NE(std::count(changed.begin(), changed.end(), true), 0) << "frame " << k << " has no inset";
    EXPECT_EQ(std::count(changed.begin(), changed.begin() + upperHalf, true), 0) << "frame " << k;
  }
  // Where the first and last plain pictures agree (the coin moved elsewhere), the insets over them
  // differ: the marker moved and the labels changed.
  const std::size_t last = inset.frames.size() - 1;
  int moved = 0;
  for (int y = 90; y < 180; ++y) {
    for (int x = 0; x < 320; ++x) {
      const bool same =
          std::equal(plain.frames[0].pixel(x, y), plain.frames[0].pixel(x, y) + 4, plain.frames[last].pixel(x, y));
      if (same &&
          !std::equal(inset.frames[0].pixel(x, y), inset.frames[0].pixel(x, y) + 4, inset.frames[last].pixel(x, y)))
        ++moved;
    }
  }
  EXPECT_GT(moved, 90) << "the marker (90 rows high at most) and the labels did not change";
}

TEST(RenderVideo, AWindowWithoutFramesIsRefusedNamingTheOptions) {
  const scene::SceneConfig scene = toyScene(1.0, 1.0);
  RecordingSink sink;
  try {
    pipeline::renderVideo(scene, sink, {.window = {.from = 0.51, .to = 0.52}});
    ADD_FAILURE() << "no frame lies in 0.51 .. 0.52 s at 10 fps";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--from 0.51 --to 0.52"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(sink.frames.empty());
  EXPECT_EQ(sink.finishes, 0);
}

// Keeps the sound track and counts the frames.
class AudioRecordingSink final : public video::FrameSink {
 public:
  void push(const image::Image&) override { ++frames; }
  void pushAudio(std::span<const float> block) override { samples.insert(samples.end(), block.begin(), block.end()); }
  void finish() override {}
  long frames = 0;
  std::vector<float> samples;
};

scene::SceneConfig sceneWithSound(int fps) {
  scene::SceneConfig scene = toyScene(1.0, 1.0);
  scene.render.fps = fps;
  scene.render.audio = scene::AudioSpec{};  // clicks: a click at full volume at phase 0, the very first sample
  return scene;
}

TEST(RenderVideo, TheSoundTrackLastsExactlyAsLongAsTheVideo) {
  // N frames at fps play for N / fps s: floor(N * 48000 / fps) samples in exact integer arithmetic,
  // also when fps does not divide 48000 (7 fps: 6857.14... samples per frame).
  for (const int fps : {7, 10, 30}) {
    AudioRecordingSink sink;
    pipeline::renderVideo(sceneWithSound(fps), sink);
    ASSERT_EQ(sink.frames, fps + 1) << fps << " fps";  // 1 s at time scale 1, both ends
    EXPECT_EQ(static_cast<long>(sink.samples.size()), sink.frames * video::kAudioSampleRate / fps) << fps << " fps";
  }
}

TEST(RenderVideo, AWindowsSoundIsTheFullTracksStretchUnderItsFrames) {
  AudioRecordingSink full, window;
  pipeline::renderVideo(sceneWithSound(10), full);
  pipeline::renderVideo(sceneWithSound(10), window, {.window = {.from = 0.3, .to = 0.6}});
  ASSERT_EQ(window.frames, 4);  // 0.3, 0.4, 0.5, 0.6 s
  const std::size_t perFrame = video::kAudioSampleRate / 10;
  ASSERT_EQ(window.samples.size(), 4 * perFrame);  // as long as its frames play
  for (std::size_t i = 0; i < window.samples.size(); ++i) {
    ASSERT_EQ(window.samples[i], full.samples[3 * perFrame + i]) << "sample " << i;
  }
}

TEST(RenderVideo, TheSoundTrackFadesInFromAndOutToSilence) {
  // Raised-cosine fades of kFadeSeconds at both ends (docs/sound.md): sample i of the fade is at
  // most volume (1 - cos(pi i / L)) / 2, so the track starts and ends at exactly 0, without the
  // click at phase 0 the clicks timbre would otherwise begin with.
  AudioRecordingSink sink;
  const scene::SceneConfig scene = sceneWithSound(10);
  pipeline::renderVideo(scene, sink);
  const auto fade = static_cast<std::size_t>(pipeline::kFadeSeconds * video::kAudioSampleRate);
  ASSERT_GT(sink.samples.size(), 2 * fade);
  const double volume = scene.render.audio->volume;
  for (std::size_t i = 0; i < fade; ++i) {
    const double ramp = 0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(i) / static_cast<double>(fade));
    EXPECT_LE(std::abs(sink.samples[i]), volume * ramp + 1e-6) << "sample " << i;
    EXPECT_LE(std::abs(sink.samples[sink.samples.size() - 1 - i]), volume * ramp + 1e-6)
        << "sample " << i << " from the end";
  }
  EXPECT_EQ(sink.samples.front(), 0.0f);
  EXPECT_EQ(sink.samples.back(), 0.0f);
}

scene::SceneConfig fallingScene(double duration) {
  // A coin let go at 60 degrees with a slow spin falls to the Euler angles' coin-flat stop (89 deg).
  nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
      {"initial", {{"theta", 60}, {"omega_Z", 0.1}}},
      {"duration", duration},
      {"render", {{"width", 96}, {"height", 64}, {"fps", 10}, {"msaa", 1}}},
  };
  return scene::parseScene(doc, "test");
}

TEST(SurveyMotion, FindsAStopInTheLastTraceIntervalOfTheRun) {
  // Where the run stops is known from the trajectory itself; a scene whose duration ends a
  // microsecond after that stop must still be surveyed as stopping there, and render to it.
  pipeline::CoinRun free(pipeline::buildSimulation(fallingScene(1.0)));
  ASSERT_FALSE(free.stateAt(1.0).has_value());
  ASSERT_TRUE(free.stoppedBy().has_value());
  const double stop = free.stoppedBy()->t;
  ASSERT_EQ(free.stoppedBy()->event, physics::ModelEvent::CoinFlat);

  const scene::SceneConfig scene = fallingScene(stop + 1e-6);
  const pipeline::MotionSurvey survey = pipeline::surveyMotion(pipeline::buildSimulation(scene));
  ASSERT_TRUE(survey.stoppedBy.has_value());
  EXPECT_EQ(survey.stoppedBy->event, physics::ModelEvent::CoinFlat);
  EXPECT_DOUBLE_EQ(survey.endTime, stop);
  RecordingSink sink;
  const pipeline::VideoRunResult result = pipeline::renderVideo(scene, sink);
  EXPECT_TRUE(result.stopDescription.has_value());
  EXPECT_EQ(result.frames, pipeline::frameCount(stop, 1.0, 10));
}

TEST(RenderVideo, CancellationLeavesTheSinkUnfinished) {
  const scene::SceneConfig scene = toyScene(1.0, 1.0);
  RecordingSink sink;
  std::atomic<bool> cancel{false};
  EXPECT_THROW(pipeline::renderVideo(scene, sink,
                                     {.onFrame =
                                          [&](const pipeline::FrameProgress& p) {
                                            if (p.frame == 3) cancel = true;
                                          },
                                      .cancel = &cancel}),
               pipeline::Cancelled);
  EXPECT_EQ(sink.frames.size(), 3u);
  EXPECT_EQ(sink.finishes, 0);
}

}  // namespace
