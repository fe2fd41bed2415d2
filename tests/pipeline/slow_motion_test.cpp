// Slow motion in the air and at each impact (render.time_remap.flight and .impact; slow_motion.h)
// against the rule computed here from a run of our own: flight frames a time_scale x slow / fps
// apart, the rate eased to the impact's slow at each impact and back, no jump in the rate from one
// frame to the next beyond the ease's bound, and a scene without the new keys given today's frame times.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "pipeline/coin_run.h"
#include "pipeline/motion_survey.h"
#include "pipeline/slow_motion.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

constexpr double kFlightSlow = 0.25, kImpactSlow = 0.05, kWindow = 0.1;  // -, -, s
constexpr int kFps = 60;

// examples/coin_toss.json to 0.8 s (the flight, the ten bounces and 0.29 s of rolling after them),
// with `remap` as its render.time_remap (none when null).
scene::SceneConfig tossScene(const nlohmann::json& remap) {
  std::ifstream in(std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["duration"] = 0.8;
  doc["render"] = {{"fps", kFps}, {"width", 64}, {"height", 36}};
  if (!remap.is_null()) doc["render"]["time_remap"] = remap;
  return scene::parseScene(doc, "test");
}

const nlohmann::json kFlightAndImpact = {{"flight", {{"slow", kFlightSlow}, {"window", kWindow}}},
                                         {"impact", {{"slow", kImpactSlow}, {"window", kWindow}}}};

// The ease written out again: slow + (1 - slow) (3 x^2 - 2 x^3), x = distance / window, 1 beyond the window.
double easedRate(double slow, double distance) {
  if (distance >= kWindow) return 1;
  const double x = distance / kWindow;
  return slow + (1 - slow) * (3 * x * x - 2 * x * x * x);
}

// The impact times and the flight flag at t, from a run of the toss of our own.
std::vector<double> impactTimes(const pipeline::Simulation& simulation) {
  pipeline::CoinRun run(simulation);
  run.sampleAt(simulation.duration);
  std::vector<double> times;
  for (const pipeline::ImpactRecord& impact : run.impacts()) times.push_back(impact.t);
  return times;
}

double distanceToNearest(const std::vector<double>& times, double t) {
  double distance = std::numeric_limits<double>::infinity();
  for (const double time : times) distance = std::min(distance, std::abs(time - t));
  return distance;
}

TEST(SlowMotion, EasesFromSlowToOneWithNoJumpInTheRateOrItsSlope) {
  const scene::EventSlowDown slowDown{.slow = 0.04, .window = kWindow};
  EXPECT_EQ(pipeline::easedMultiplier(slowDown, 0), 0.04);
  EXPECT_EQ(pipeline::easedMultiplier(slowDown, kWindow), 1);
  EXPECT_EQ(pipeline::easedMultiplier(slowDown, 1), 1);
  EXPECT_NEAR(pipeline::easedMultiplier(slowDown, kWindow / 2), 0.52, 1e-15);  // half-way: half-way
  // The multiplier's slope in simulated time: (1 - slow) 6 x (1 - x) / window, 1.5 (1 - slow) / window
  // at the middle, 0 at both ends.
  const double steepest = 1.5 * (1 - 0.04) / kWindow, h = 1e-8;
  const auto slope = [&](double d) {
    return (pipeline::easedMultiplier(slowDown, d + h) - pipeline::easedMultiplier(slowDown, d)) / h;
  };
  EXPECT_NEAR(slope(kWindow / 2), steepest, 1e-6 * steepest);
  EXPECT_LT(slope(0), 1e-5 * steepest);
  EXPECT_LT(slope(kWindow - h), 1e-5 * steepest);
  // A window of 0 switches at once.
  EXPECT_EQ(pipeline::easedMultiplier({.slow = 0.5, .window = 0}, 0), 0.5);
  EXPECT_EQ(pipeline::easedMultiplier({.slow = 0.5, .window = 0}, 1e-12), 1);
}

TEST(SlowMotion, TheScheduleHoldsTheRunsImpactsAndEveryMomentInTheAir) {
  const scene::SceneConfig scene = tossScene(kFlightAndImpact);
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  const pipeline::SlowMotionSchedule schedule = pipeline::planSlowMotion(scene, simulation);
  EXPECT_EQ(schedule.impacts, impactTimes(simulation));
  ASSERT_EQ(schedule.impacts.size(), 10u);
  ASSERT_FALSE(schedule.flights.empty());
  // Sampled every 0.1 ms here: each moment in the air lies in a stretch, and each stretch starts
  // within a grid step (traceInterval) before its first such moment and ends at an impact.
  pipeline::CoinRun run(simulation);
  const double grid = pipeline::traceInterval(simulation.duration);
  std::vector<double> firstInTheAir(schedule.flights.size(), std::numeric_limits<double>::infinity());
  for (int i = 0; i <= 8000; ++i) {
    const double t = i * 1e-4;
    const std::optional<pipeline::RunSample> sample = run.sampleAt(t);
    ASSERT_TRUE(sample.has_value());
    if (!sample->forward.flying) continue;
    const auto in = std::find_if(schedule.flights.begin(), schedule.flights.end(),
                                 [&](const auto& span) { return span.start <= t && t <= span.end; });
    ASSERT_NE(in, schedule.flights.end()) << "in the air at t = " << t << " s outside every stretch";
    double& first = firstInTheAir[static_cast<std::size_t>(in - schedule.flights.begin())];
    first = std::min(first, t);
  }
  for (std::size_t j = 0; j < schedule.flights.size(); ++j) {
    EXPECT_LE(firstInTheAir[j] - schedule.flights[j].start, grid + 1e-4) << "stretch " << j;
    EXPECT_NE(std::find(schedule.impacts.begin(), schedule.impacts.end(), schedule.flights[j].end),
              schedule.impacts.end())
        << "stretch " << j << " ends at " << schedule.flights[j].end << " s, no impact";
  }
  // The toss: one stretch, from the hand to the bounce-end.
  EXPECT_EQ(schedule.flights.front().start, 0);
  EXPECT_EQ(schedule.flights.back().end, schedule.impacts.back());
}

TEST(SlowMotion, ThePlanFollowsTheFlightAndImpactRuleComputedHere) {
  const scene::SceneConfig scene = tossScene(kFlightAndImpact);
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  const std::vector<double> impacts = impactTimes(simulation);
  const pipeline::RunRecord record = pipeline::recordFrames(scene, simulation);
  const std::vector<pipeline::FrameState>& frames = record.frames;
  ASSERT_GT(frames.size(), 150u);
  const double lastImpact = impacts.back();
  int inFlight = 0, eased = 0, realTime = 0;
  std::vector<double> rates;  // simulated s per video s, each frame's step to the next times fps
  for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
    const double t = frames[k].time, rate = (frames[k + 1].time - t) * kFps;
    rates.push_back(rate);
    const double atImpact = easedRate(kImpactSlow, distanceToNearest(impacts, t));
    // In the air, the flight's rate or the impact's, the slower; on the floor after the last landing,
    // the impact's ease (the flight's, over the same window from the same landing, is less slow).
    const double expected = frames[k].flying ? std::min(kFlightSlow, atImpact) : atImpact;
    if (!frames[k].flying) {
      ASSERT_GT(t, lastImpact) << "on the floor before the bounces end, frame " << k;
    }
    EXPECT_NEAR(rate, expected, 1e-9) << "frame " << k << " at t = " << t << " s";
    if (std::abs(rate - kFlightSlow) < 1e-9)
      ++inFlight;
    else if (rate < 1 - 1e-9)
      ++eased;
    else
      ++realTime;
  }
  // The flight from the hand, 0.395 s at a quarter of real time, its last 0.03 s slowed further for the
  // landing: about 88 frames 1/240 s apart.
  EXPECT_GE(inFlight, 80);
  EXPECT_GT(eased, 50);
  EXPECT_GT(realTime, 5);
  // At each impact the rate comes down to the impact's slow: the frame nearest it is within half a
  // slow step, where the ease has barely begun.
  for (const double impact : impacts) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < rates.size(); ++k) {
      if (std::abs(frames[k].time - impact) <= kImpactSlow / kFps) nearest = std::min(nearest, rates[k]);
    }
    EXPECT_LE(nearest, 1.01 * kImpactSlow) << "impact at t = " << impact << " s";
  }
  // No jump: the multiplier m climbs at most 1.5 (1 - slow) / window per simulated second and a frame
  // moves on by m time_scale / fps, so from one frame to the next ln(rate) changes by at most
  // B = 1.5 (1 - slow) time_scale / (window fps) times m(here) / m(there) <= e^(that change): within B e^(2B).
  const double bound = 1.5 * (1 - kImpactSlow) / (kWindow * kFps);
  double largest = 0;
  for (std::size_t k = 0; k + 1 < rates.size(); ++k) {
    largest = std::max(largest, std::abs(std::log(rates[k + 1] / rates[k])));
  }
  EXPECT_LE(largest, bound * std::exp(2 * bound));
  EXPECT_GT(largest, 0.5 * bound);  // the bound is near what the ease does
}

TEST(SlowMotion, WithoutTheNewKeysTheFrameTimesAreTodays) {
  // No time remap: k time_scale / fps, exactly.
  const scene::SceneConfig plain = tossScene(nullptr);
  const pipeline::Simulation simulation = pipeline::buildSimulation(plain);
  const pipeline::RunRecord record = pipeline::recordFrames(plain, simulation);
  ASSERT_EQ(static_cast<long>(record.frames.size()), pipeline::frameCount(record.survey.endTime, 1, kFps));
  for (std::size_t k = 0; k < record.frames.size(); ++k) {
    EXPECT_EQ(record.frames[k].time, static_cast<double>(k) * (1.0 / kFps)) << "frame " << k;
  }
  // A rate rule alone: t_(k+1) = t_k + playbackRate(|psi-dot at t_k|) / fps, summed as before, to the bit.
  const scene::SceneConfig spin = tossScene({{"spin_rate", 5}});
  const pipeline::RunRecord remapped = pipeline::recordFrames(spin, pipeline::buildSimulation(spin));
  pipeline::CoinRun run(simulation);
  double t = 0;
  for (std::size_t k = 0; k < remapped.frames.size(); ++k) {
    ASSERT_EQ(remapped.frames[k].time, t) << "frame " << k;
    t += pipeline::playbackRate(spin.render, std::abs(run.sampleAt(t)->forward.spinRate)) / kFps;
  }
  EXPECT_LT(remapped.frames.size(), 10 * record.frames.size());  // the rule slowed it, within reason
  EXPECT_GT(remapped.frames.size(), record.frames.size());
}

TEST(SlowMotion, ACoinThatNeverFliesIsNotSlowedNorRunTwice) {
  scene::SceneConfig scene = tossScene(kFlightAndImpact);
  pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  simulation.flight = false;
  const pipeline::SlowMotionSchedule schedule = pipeline::planSlowMotion(scene, simulation);
  EXPECT_TRUE(schedule.flights.empty());
  EXPECT_TRUE(schedule.impacts.empty());
  EXPECT_EQ(pipeline::scheduledSlowDown(scene.render, schedule, 0.3).multiplier, 1);
  EXPECT_EQ(pipeline::scheduledSlowDown(scene.render, schedule, 0.3).by, pipeline::SlowedBy::Nothing);
}

}  // namespace
