#include "pipeline/playback_clock.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace coinroll::pipeline {

long frameCount(double simulatedSeconds, double timeScale, int fps) {
  // The nudge keeps a frame that falls on the end despite round-off: 0.3 s at time_scale 0.1 and
  // 30 fps is 90 frame intervals, but 0.3 / 0.1 * 30 is 89.99999999999999 in binary (0.3 and 0.1
  // are both rounded), which alone would give 90 frames instead of 91.
  return static_cast<long>(std::floor(simulatedSeconds / timeScale * fps * (1 + 1e-12) + 1e-9)) + 1;
}

bool isRemapped(const scene::RenderSpec& render) {
  return render.timeRemap || render.flightSlowDown || render.impactSlowDown;
}

double playbackRate(const scene::RenderSpec& render, double rate) {
  if (!render.timeRemap || !(rate > render.timeRemap->limit)) return render.timeScale;
  const scene::TimeRemap& remap = *render.timeRemap;
  const double held = render.timeScale * remap.limit;
  const double quarterTurnPerFrame = std::numbers::pi / 2 * render.fps;
  const double visible =
      std::max(held, std::min(held * std::pow(rate / remap.limit, remap.growth), quarterTurnPerFrame));
  return std::min(render.timeScale, visible / rate);
}

ClipRate clipRateAt(const scene::RenderSpec& render, const SlowMotionSchedule& schedule, double t, double spinRate,
                    double precessionRate) {
  ClipRate clip{.rate = render.timeScale};
  if (render.timeRemap) {
    const bool bySpin = render.timeRemap->rate == scene::TimeRemap::Rate::Spin;
    clip.rate = playbackRate(render, std::abs(bySpin ? spinRate : precessionRate));
    if (clip.rate < render.timeScale) clip.by = SlowedBy::Rate;
  }
  if (render.flightSlowDown || render.impactSlowDown) {
    // Slower still where the coin flies or an impact is near.
    if (const ScheduledSlowDown scheduled = scheduledSlowDown(render, schedule, t);
        render.timeScale * scheduled.multiplier < clip.rate) {
      clip = {.rate = render.timeScale * scheduled.multiplier, .by = scheduled.by};
    }
  }
  return clip;
}

namespace {

// `raisedWith`: how the caller's user raises the limit; empty when they cannot.
[[noreturn]] void refuseFrames(const scene::SceneConfig& scene, long maxFrames, std::string_view raisedWith,
                               const std::string& count) {
  const std::string fixes = raisedWith.empty() ? "shorten the duration, raise time_scale or lower fps"
                                               : fmt::format(
                                                     "shorten the duration, raise time_scale or lower fps, or "
                                                     "raise the limit with {}",
                                                     raisedWith);
  throw std::invalid_argument(
      fmt::format("render: duration {} s at time_scale {}, fps {}{} gives {} frames, more than the limit {}; {}",
                  scene.duration, scene.render.timeScale, scene.render.fps,
                  isRemapped(scene.render) ? " and the time remap" : "", count, maxFrames, fixes));
}

// The clip's frames, chosen inside the pass: k time_scale / fps, or with a time remap
// t_(k+1) = t_k + rate_k / fps up to the run's end, rate_k the slowest of the rate rule's at frame k's
// sample and the flight and impact slow-downs' at t_k (from `schedule`, known ahead).
class ClipFrameTimes final : public FramePlan {
 public:
  ClipFrameTimes(const scene::SceneConfig& scene, long maxFrames, std::string_view maxFramesOption,
                 const SlowMotionSchedule& schedule)
      : scene_(scene),
        schedule_(schedule),
        maxFrames_(maxFrames),
        maxFramesOption_(maxFramesOption),
        perFrame_(scene.render.timeScale / scene.render.fps),
        ofDuration_(frameCount(scene.duration, scene.render.timeScale, scene.render.fps)) {}

  std::optional<double> timeOf(long k, const RunSample* previous) override {
    const scene::RenderSpec& render = scene_.render;
    if (!isRemapped(render)) {
      // Past the limit frames are not recorded: the refusal needs the count to the run's end (recordFrames).
      if (k >= ofDuration_ || k >= maxFrames_) return std::nullopt;
      return static_cast<double>(k) * perFrame_;
    }
    if (k == 0) return 0.0;
    if (previous == nullptr) return std::nullopt;  // the run ended at frame k - 1
    // Frame k - 1's rates: the step to frame k is its playback rate.
    const ClipRate clip =
        clipRateAt(render, schedule_, lastTime_, previous->forward.spinRate, previous->forward.precessionRate);
    slowedBy_.push_back(clip.by);
    return lastTime_ += clip.rate / render.fps;
  }

  bool keeps(long k, double time, double end) override {
    if (!isRemapped(scene_.render)) return k < frameCount(end, scene_.render.timeScale, scene_.render.fps);
    // The sum of steps drifts by round-off; a relative 1e-12 keeps the frame at the very end.
    if (time > end * (1 + 1e-12)) return false;
    if (k == maxFrames_) {
      refuseFrames(scene_, maxFrames_, maxFramesOption_,
                   fmt::format("more than {} (the time remap slows it at t = {:.6g} s)", maxFrames_, time));
    }
    return true;
  }

  // The rule that set each frame's step to the next, for the frames asked so far.
  std::vector<SlowedBy> slowedBy() && { return std::move(slowedBy_); }

 private:
  const scene::SceneConfig& scene_;
  const SlowMotionSchedule& schedule_;
  long maxFrames_;
  std::string_view maxFramesOption_;
  double perFrame_;      // s of simulated time, without a remap
  long ofDuration_;      // frames of a run that lasts its duration, without a remap
  double lastTime_ = 0;  // s, the remapped frame time last given
  std::vector<SlowedBy> slowedBy_;
};

}  // namespace

ClipRecord recordClip(const scene::SceneConfig& scene, const Simulation& simulation, long maxFrames,
                      std::string_view maxFramesOption) {
  ClipRecord clip{.record = {}, .slowedBy = {}, .schedule = planSlowMotion(scene, simulation)};
  ClipFrameTimes plan(scene, maxFrames, maxFramesOption, clip.schedule);
  clip.record = recordRun(simulation, plan);
  if (!isRemapped(scene.render)) {
    if (const long total = frameCount(clip.record.survey.endTime, scene.render.timeScale, scene.render.fps);
        total > maxFrames) {
      refuseFrames(scene, maxFrames, maxFramesOption, std::to_string(total));
    }
  }
  clip.slowedBy = std::move(plan).slowedBy();
  return clip;
}

RunRecord recordFrames(const scene::SceneConfig& scene, const Simulation& simulation, long maxFrames) {
  return recordClip(scene, simulation, maxFrames, kMaxFramesOption).record;
}

void refuseAbsurdDuration(const scene::SceneConfig& scene, long maxFrames, std::string_view maxFramesOption) {
  if (const double atMost = static_cast<double>(scene.duration) / scene.render.timeScale * scene.render.fps;
      atMost > kUpFrontFrameFactor * static_cast<double>(maxFrames)) {
    refuseFrames(scene, maxFrames, maxFramesOption, fmt::format("{:.4g}", atMost));
  }
}

ClipPlan planOf(const scene::SceneConfig& scene, ClipRecord& clip) {
  RunRecord& record = clip.record;
  const MotionSurvey& survey = record.survey;
  std::vector<FrameState>& frames = record.frames;
  ClipPlan plan;
  plan.fps = scene.render.fps;
  plan.timeScale = scene.render.timeScale;
  plan.remapped = isRemapped(scene.render);
  plan.byEvents = scene.render.flightSlowDown || scene.render.impactSlowDown;
  plan.flights = std::move(clip.schedule.flights);
  plan.impacts = std::move(clip.schedule.impacts);
  plan.endTime = survey.endTime;
  if (survey.stoppedBy) plan.stopDescription = describeStop(*survey.stoppedBy);
  plan.landed = survey.stoppedBy && survey.stoppedBy->event == physics::ModelEvent::FaceDown;
  const bool landingFrameAdded = plan.landed && frames.back().time < survey.endTime;
  if (landingFrameAdded) frames.push_back(record.end);
  plan.simulatedFrames = static_cast<long>(frames.size());
  const long holdFrames = plan.landed ? std::lround(kLandingHoldSeconds * scene.render.fps) : 0;
  // The playback rate is the step to the next frame times fps. The clip's last planned frame and an
  // added landing frame keep the pace of the frame before (a remapped clip's end is still in slow
  // motion), not that of the short step to the landing; simulated time stands still in the hold.
  const std::size_t lastPlanned = frames.size() - (landingFrameAdded ? 2 : 1);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const double step = k < lastPlanned   ? frames[k + 1].time - frames[k].time
                        : lastPlanned > 0 ? frames[lastPlanned].time - frames[lastPlanned - 1].time
                                          : scene.render.timeScale / scene.render.fps;
    plan.times.push_back(frames[k].time);
    plan.playbackRates.push_back(step * scene.render.fps);
    plan.contactRates.push_back(std::abs(frames[k].precessionRate));
    // The rule behind the step, which the last frames keep as they keep its pace.
    const std::size_t stepFrom = k < lastPlanned ? k : lastPlanned > 0 ? lastPlanned - 1 : 0;
    plan.slowedBy.push_back(stepFrom < clip.slowedBy.size() ? clip.slowedBy[stepFrom] : SlowedBy::Nothing);
  }
  plan.times.insert(plan.times.end(), holdFrames, survey.endTime);
  plan.playbackRates.insert(plan.playbackRates.end(), holdFrames, 0.0);
  plan.contactRates.insert(plan.contactRates.end(), holdFrames, plan.contactRates.back());
  plan.slowedBy.insert(plan.slowedBy.end(), holdFrames, SlowedBy::Nothing);
  return plan;
}

ClipPlan planClip(const scene::SceneConfig& scene, long maxFrames, const std::atomic<bool>* cancel) {
  refuseAbsurdDuration(scene, maxFrames, kMaxFramesOption);
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = cancel;
  ClipRecord clip = recordClip(scene, simulation, maxFrames, kMaxFramesOption);
  return planOf(scene, clip);
}

}  // namespace coinroll::pipeline
