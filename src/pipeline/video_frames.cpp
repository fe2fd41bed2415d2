#include "pipeline/video_frames.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pipeline/coin_sound.h"
#include "pipeline/motion_survey.h"
#include "pipeline/run_record.h"
#include "pipeline/resources.h"
#include "pipeline/simulation.h"
#include "pipeline/slow_motion.h"
#include "pipeline/snapshot.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

long frameCount(double simulatedSeconds, double timeScale, int fps) {
  // The nudge keeps a frame that falls on the end despite round-off: 0.3 s at time_scale 0.1 and
  // 30 fps is 90 frame intervals, but 0.3 / 0.1 * 30 is 89.99999999999999 in binary (0.3 and 0.1
  // are both rounded), which alone would give 90 frames instead of 91.
  return static_cast<long>(std::floor(simulatedSeconds / timeScale * fps * (1 + 1e-12) + 1e-9)) + 1;
}

namespace {

// Whether a rule of render.time_remap may slow the clip: frame times are then summed step by step.
bool isRemapped(const scene::RenderSpec& render) {
  return render.timeRemap || render.flightSlowDown || render.impactSlowDown;
}

// `raisedWith`: how the caller's user raises the limit; empty when they cannot.
[[noreturn]] void refuseFrames(const scene::SceneConfig& scene, long maxFrames, std::string_view raisedWith,
                               const std::string& count) {
  const std::string fixes = raisedWith.empty() ? "shorten the duration, raise time_scale or lower fps"
                                               : fmt::format("shorten the duration, raise time_scale or lower fps, or "
                                                             "raise the limit with {}", raisedWith);
  throw std::invalid_argument(fmt::format(
      "render: duration {} s at time_scale {}, fps {}{} gives {} frames, more than the limit {}; {}", scene.duration,
      scene.render.timeScale, scene.render.fps, isRemapped(scene.render) ? " and the time remap" : "", count, maxFrames,
      fixes));
}

}  // namespace

double playbackRate(const scene::RenderSpec& render, double rate) {
  if (!render.timeRemap || !(rate > render.timeRemap->limit)) return render.timeScale;
  const scene::TimeRemap& remap = *render.timeRemap;
  const double held = render.timeScale * remap.limit;
  const double quarterTurnPerFrame = std::numbers::pi / 2 * render.fps;
  const double visible =
      std::max(held, std::min(held * std::pow(rate / remap.limit, remap.growth), quarterTurnPerFrame));
  return std::min(render.timeScale, visible / rate);
}

namespace {

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
    double rate = render.timeScale;
    SlowedBy by = SlowedBy::Nothing;
    if (render.timeRemap) {
      const bool bySpin = render.timeRemap->rate == scene::TimeRemap::Rate::Spin;
      rate = playbackRate(render, std::abs(bySpin ? previous->forward.spinRate : previous->forward.precessionRate));
      if (rate < render.timeScale) by = SlowedBy::Rate;
    }
    if (render.flightSlowDown || render.impactSlowDown) {
      // Slower still where the coin flies or an impact is near: the rule's rate at frame k's time.
      if (const ScheduledSlowDown scheduled = scheduledSlowDown(render, schedule_, lastTime_);
          render.timeScale * scheduled.multiplier < rate) {
        rate = render.timeScale * scheduled.multiplier;
        by = scheduled.by;
      }
    }
    slowedBy_.push_back(by);  // frame k - 1's rule: the step to frame k is its playback rate
    return lastTime_ += rate / render.fps;
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
  double perFrame_;    // s of simulated time, without a remap
  long ofDuration_;    // frames of a run that lasts its duration, without a remap
  double lastTime_ = 0;  // s, the remapped frame time last given
  std::vector<SlowedBy> slowedBy_;
};

// The one pass's record and what the plan reports besides: the rule behind each frame's rate and
// the flight and impact schedule it followed.
struct ClipRecord {
  RunRecord record;
  std::vector<SlowedBy> slowedBy;
  SlowMotionSchedule schedule;
};

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

}  // namespace

RunRecord recordFrames(const scene::SceneConfig& scene, const Simulation& simulation, long maxFrames) {
  return recordClip(scene, simulation, maxFrames, kMaxFramesOption).record;
}

namespace {

// The sound track, produced frame by frame from the states the pictures use: the block between
// frames k - 1 and k is synthesised when frame k's state is known, its pitch moving linearly
// between the two frames' (docs/sound.md §2).
class SoundTrack {
 public:
  // `impactScale`: the energy an impact must take to knock at full volume, J.
  SoundTrack(const scene::AudioSpec& spec, int fps, double impactScale)
      : spec_(spec), fps_(fps), synth_(spec, video::kAudioSampleRate), impactScale_(impactScale) {}

  // An impact between the previous frame and the next one, at `fraction` of the way: it knocks in
  // the next block, its loudness the square root of its energy over impactScale, capped at 1.
  void knock(double fraction, double energyLost) { knocks_.push_back({fraction, energyLost}); }

  // Each call's block of sound ends at frame k; it goes to `sink`, or nowhere when that is null (a
  // frame outside the window), still synthesised so the sound is the full render's.
  // `landing`: frame k is the coin's landing, where the sound fades out to the silence of the hold.
  // `precessionRate`: phi-dot at frame k, rad/s.
  void reachFrame(long k, double precessionRate, double playbackRate, video::FrameSink* sink, bool landing) {
    // Omega = |phi-dot|, the contact point's rate round the floor; with pitch "video" the sound is
    // played at the picture's speed, so its frequency scales with simulated seconds per video second.
    const double rate = spec_.pitch == scene::AudioSpec::Pitch::Video ? playbackRate : 1.0;
    const double f = spec_.frequencyScale * std::abs(precessionRate) / (2 * std::numbers::pi) * rate;
    if (k > 0) emit(k, f, sink, landing);
    frequency_ = f;
  }

  // The block up to frame k of a coin lying still: silence.
  void rest(long k, video::FrameSink* sink) {
    block_.assign(static_cast<std::size_t>(sampleAt(k) - sampleAt(k - 1)), 0.0f);
    if (sink != nullptr) sink->pushAudio(block_);
  }

  // The last frame's block, so the track lasts exactly as long as the video.
  void finish(long frames, video::FrameSink* sink, bool resting) {
    if (resting) rest(frames, sink);
    else emit(frames, frequency_, sink, true);
  }

 private:
  // Sample index at which frame k starts: k * rate / fps, exact in integers.
  std::int64_t sampleAt(long k) const {
    return static_cast<std::int64_t>(k) * video::kAudioSampleRate / fps_;
  }

  void emit(long k, double f, video::FrameSink* sink, bool last) {
    block_.clear();
    synth_.synthesize(frequency_, f, static_cast<std::size_t>(sampleAt(k) - sampleAt(k - 1)), block_);
    synth_.ringOn(block_);
    for (const auto& [fraction, energy] : knocks_) {
      const auto at = static_cast<std::size_t>(fraction * static_cast<double>(block_.size()));
      synth_.addImpact(block_, std::min(at, block_.size()), std::sqrt(energy / impactScale_));
    }
    knocks_.clear();
    if (k == 1) synth_.fadeIn(block_);
    if (last) synth_.fadeOut(block_);
    if (sink != nullptr) sink->pushAudio(block_);
  }

  scene::AudioSpec spec_;
  int fps_;
  CoinSound synth_;
  double frequency_ = 0;  // Hz, at the previous frame
  std::vector<float> block_;
  double impactScale_;
  std::vector<std::pair<double, double>> knocks_;  // the next block's impacts: fraction of it, J
};

}  // namespace

namespace {

// The up-front refusal: the duration's frames bound what a run that goes the distance shows (a remap
// only adds), so absurd ones are refused before the pass over the run (kUpFrontFrameFactor).
void refuseAbsurdDuration(const scene::SceneConfig& scene, long maxFrames, std::string_view maxFramesOption) {
  if (const double atMost = static_cast<double>(scene.duration) / scene.render.timeScale * scene.render.fps;
      atMost > kUpFrontFrameFactor * static_cast<double>(maxFrames)) {
    refuseFrames(scene, maxFrames, maxFramesOption, fmt::format("{:.4g}", atMost));
  }
}

// The plan of the frames `record` holds; a coin that landed on its face gets its landing's frame
// (appended to record.frames) and then lies still for kLandingHoldSeconds, so the end is seen.
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
    const double step = k < lastPlanned  ? frames[k + 1].time - frames[k].time
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

}  // namespace

ClipPlan planClip(const scene::SceneConfig& scene, long maxFrames, const std::atomic<bool>* cancel) {
  refuseAbsurdDuration(scene, maxFrames, kMaxFramesOption);
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = cancel;
  ClipRecord clip = recordClip(scene, simulation, maxFrames, kMaxFramesOption);
  return planOf(scene, clip);
}

FrameRange framesIn(const ClipPlan& plan, const TimeWindow& window) {
  const double length = plan.videoSeconds();
  // A frame's place on the window's clock: simulated time, or video time k / fps.
  const bool byVideo = window.clock == TimeWindow::Clock::Video || window.last;
  const auto clockOf = [&](long k) {
    return byVideo ? static_cast<double>(k) / plan.fps : plan.times[static_cast<std::size_t>(k)];
  };
  if (window.last && *window.last > length + kWindowTolerance) {
    throw std::invalid_argument(fmt::format("--last {}: longer than the clip, which lasts {:.9g} s of video; give at "
                                            "most that, or no window for the whole clip",
                                            *window.last, length));
  }
  const double from = window.last ? length - *window.last : window.from;
  const double to = window.last ? length : window.to;
  FrameRange range{plan.frames(), plan.frames() - 1};
  for (long k = 0; k < plan.frames(); ++k) {
    const double t = clockOf(k);
    if (t < from - kWindowTolerance || t > to + kWindowTolerance) continue;
    range.first = std::min(range.first, k);
    range.last = k;
  }
  if (range.first <= range.last) return range;
  const double lastFrameAt = static_cast<double>(plan.frames() - 1) / plan.fps;  // s of video
  if (window.last) {
    throw std::invalid_argument(fmt::format("--last {}: no frame plays in the last {} s of the {:.6g} s clip; give "
                                            "at least one frame's length, 1 / fps = {:.6g} s",
                                            *window.last, *window.last, length, 1.0 / plan.fps));
  }
  if (byVideo && from > lastFrameAt + kWindowTolerance) {
    throw std::invalid_argument(fmt::format("--from-video {}: beyond the clip's last frame at {:.9g} s of video (the "
                                            "clip lasts {:.9g} s); give a time in [0, {:.9g}]",
                                            from, lastFrameAt, length, lastFrameAt));
  }
  if (byVideo) {
    throw std::invalid_argument(fmt::format(
        "--from-video {} --to-video {}: no frame plays in this window (frames are 1 / {} s of video apart); widen it",
        window.from, window.to, plan.fps));
  }
  if (window.from > plan.endTime + kWindowTolerance) {
    throw std::invalid_argument(fmt::format("--from {}: beyond the run's end at {:.9g} s{}; give a time in [0, {:.9g}]",
                                            window.from, plan.endTime,
                                            plan.stopDescription ? " (" + *plan.stopDescription + ")" : "",
                                            plan.endTime));
  }
  throw std::invalid_argument(fmt::format("--from {} --to {}: no frame's simulated time lies in this window (frames "
                                          "are {:.6g} s of simulated time apart{}); widen it",
                                          window.from, window.to, plan.timeScale / plan.fps,
                                          plan.remapped ? ", less where render.time_remap slows them" : ""));
}

namespace {

// A playback rate as the overlay says it: slow motion or fast forward by how much.
std::string speedOf(double rate) {
  if (rate == 0) return "landing held";
  if (rate < 1 - 1e-9) return fmt::format("slow x{:.3g}", 1 / rate);
  if (rate > 1 + 1e-9) return fmt::format("fast x{:.3g}", rate);
  return "real time";
}

// The rule a frame's rate is set by, as the plan's table names it.
std::string_view ruleOf(SlowedBy by) {
  switch (by) {
    case SlowedBy::Rate: return "rate";
    case SlowedBy::Flight: return "flight";
    case SlowedBy::Impact: return "impact";
    case SlowedBy::Nothing: break;
  }
  return "-";
}

// The flight and impact slow-downs' line of the plan: what they followed and how many frames they set.
std::string slowMotionLine(const ClipPlan& plan) {
  const auto framesBy = [&](SlowedBy by) { return std::count(plan.slowedBy.begin(), plan.slowedBy.end(), by); };
  std::vector<std::string> stretches;
  for (const SlowMotionSchedule::Span& span : plan.flights) {
    stretches.push_back(fmt::format("{:.6f} to {:.6f} s", span.start, span.end));
  }
  constexpr std::size_t kListed = 4;  // stretches named; a hopping coin may have hundreds
  if (stretches.size() > kListed) {
    stretches.resize(kListed);
    stretches.emplace_back("...");
  }
  return fmt::format("slow motion: {} frames by flight, in the air {} time{} ({}); {} frames by impact, {} impact{}{}",
                     framesBy(SlowedBy::Flight), plan.flights.size(), plan.flights.size() == 1 ? "" : "s",
                     fmt::join(stretches, ", "), framesBy(SlowedBy::Impact), plan.impacts.size(),
                     plan.impacts.size() == 1 ? "" : "s",
                     plan.impacts.empty() ? "" : fmt::format(" from {:.6f} to {:.6f} s", plan.impacts.front(),
                                                             plan.impacts.back()));
}

}  // namespace

std::vector<std::string> planLines(const ClipPlan& plan, const TimeWindow& window) {
  const long holdFrames = plan.frames() - plan.simulatedFrames;
  std::vector<std::string> lines;
  lines.push_back(fmt::format("video: {} frames at {} fps, {:.3f} s{}", plan.frames(), plan.fps, plan.videoSeconds(),
                              holdFrames > 0 ? fmt::format(" (the last {} hold the landing, {:g} s)", holdFrames,
                                                           kLandingHoldSeconds)
                                             : ""));
  lines.push_back(fmt::format("simulated: 0 to {:.6f} s{}", plan.endTime,
                              plan.stopDescription ? "; the run stops early: " + *plan.stopDescription : ""));
  if (plan.byEvents) lines.push_back(slowMotionLine(plan));
  const FrameRange range = framesIn(plan, window);
  const auto first = static_cast<std::size_t>(range.first), last = static_cast<std::size_t>(range.last);
  const long written = range.last - range.first + 1;
  lines.push_back(fmt::format("written: {} frames {} to {}, {:.3f} s of video from {:.3f} s; simulated {:.6f} to "
                              "{:.6f} s",
                              written == plan.frames() ? "all" : std::to_string(written), range.first, range.last,
                              static_cast<double>(written) / plan.fps, static_cast<double>(range.first) / plan.fps,
                              plan.times[first], plan.times[last]));
  // A row where the playback rate or the contact point's rate has changed by kRowChange since the
  // last row; a wobbling run whose rates swing by more would list most of its frames, so the step
  // grows until the table is small.
  constexpr double kRowChange = 1.25;
  constexpr std::size_t kMaxRows = 24;
  const auto changed = [](double now, double before, double factor) {
    return now > 0 && before > 0 ? std::max(now / before, before / now) >= factor : (now > 0) != (before > 0);
  };
  std::vector<std::size_t> rows;
  for (double factor = kRowChange; rows.empty() || rows.size() > kMaxRows; factor *= kRowChange) {
    rows = {0};
    for (std::size_t k = 1; k < plan.times.size(); ++k) {
      const std::size_t row = rows.back();
      if (changed(plan.playbackRates[k], plan.playbackRates[row], factor) ||
          changed(plan.contactRates[k], plan.contactRates[row], factor) || k + 1 == plan.times.size()) {
        rows.push_back(k);
      }
    }
  }
  lines.emplace_back("playback over the clip (a row where a rate changed by 25 % or more; rate: simulated s per "
                     "video s; contact: the contact point round the floor, turns per s; slowed_by: the time remap's "
                     "rule that set the rate):");
  lines.emplace_back(
      "    frame    video_s        sim_s       rate        speed  contact_Hz  contact_turns_per_video_s  slowed_by");
  for (const std::size_t k : rows) {
    const double rate = plan.playbackRates[k], turns = plan.contactRates[k] / (2 * std::numbers::pi);
    lines.push_back(fmt::format("{:9d} {:10.3f} {:12.6f} {:10.6f} {:>12} {:11.3f} {:26.3f}  {:>9}", k,
                                static_cast<double>(k) / plan.fps, plan.times[k], rate,
                                speedOf(rate), turns, turns * rate, ruleOf(plan.slowedBy[k])));
  }
  return lines;
}

namespace {

// Points per inset curve: a few per pixel of a 1080p plot, which a clip of a million frames would
// otherwise carry into every frame's overlay.
constexpr std::size_t kInsetPoints = 600;
// A contact rate spanning this factor or more is plotted on a log scale, where an Euler's disk's
// finite-time speed-up is a curve that steepens instead of a flat line and a wall.
constexpr double kLogScaleSpan = 4;

// The inset (render --inset) of the frames `range` of `plan`, the video written: the contact point's
// rate (Hz) and the tilt above the floor (degrees, from 0) against video time, each over its range
// within those frames (the last 20 s of the Euler's disk fill the plot), and each frame's labels.
class ClipInset {
 public:
  ClipInset(const ClipPlan& plan, const std::vector<FrameState>& frames, FrameRange range)
      : plan_(plan), frames_(frames), range_(range) {
    for (long k = range.first; k <= range.last; ++k) {
      rateMin_ = std::min(rateMin_, hertz(k));
      rateMax_ = std::max(rateMax_, hertz(k));
      tiltMax_ = std::max(tiltMax_, tiltDegrees(k));
    }
    logRate_ = rateMin_ > 0 && rateMax_ >= kLogScaleSpan * rateMin_;
  }

  render::InsetPlot plot() const {
    render::InsetPlot plot{.curves = {{}, {}}};
    const long count = range_.last - range_.first + 1;
    const long stride = std::max(1L, (count + static_cast<long>(kInsetPoints) - 1) / static_cast<long>(kInsetPoints));
    // Every stride-th frame, and the last.
    for (long k = range_.first;; k = std::min(k + stride, range_.last)) {
      const float x = progress(k);
      plot.curves[0].points.emplace_back(x, static_cast<float>(rateScaled(hertz(k))));
      plot.curves[1].points.emplace_back(x, static_cast<float>(tiltMax_ > 0 ? tiltDegrees(k) / tiltMax_ : 0));
      if (k == range_.last) break;
    }
    return plot;
  }

  float progress(long k) const {
    return range_.last > range_.first
               ? static_cast<float>(k - range_.first) / static_cast<float>(range_.last - range_.first)
               : 0.0f;
  }

  std::vector<std::string> labels(long k) const {
    return {fmt::format("contact {:6.1f} Hz  ({}{:.3g} to {:.3g} Hz)", hertz(k), logRate_ ? "log, " : "", rateMin_,
                        rateMax_),
            fmt::format("tilt    {:6.2f}°   (0 to {:.3g}° above the floor)", tiltDegrees(k), tiltMax_)};
  }

 private:
  double hertz(long k) const { return plan_.contactRates[static_cast<std::size_t>(k)] / (2 * std::numbers::pi); }
  double tiltDegrees(long k) const {
    const std::size_t shown = std::min(static_cast<std::size_t>(k), frames_.size() - 1);  // the hold: the landing
    return 90 - frames_[shown].theta * 180 / std::numbers::pi;
  }
  double rateScaled(double value) const {
    if (logRate_) return std::log(value / rateMin_) / std::log(rateMax_ / rateMin_);
    return rateMax_ > 0 ? value / rateMax_ : 0;
  }

  const ClipPlan& plan_;
  const std::vector<FrameState>& frames_;
  FrameRange range_;
  double rateMin_ = std::numeric_limits<double>::infinity(), rateMax_ = 0, tiltMax_ = 0;  // Hz, Hz, degrees
  bool logRate_ = false;
};

}  // namespace

VideoRunResult renderVideo(const scene::SceneConfig& scene, video::FrameSink& sink, const VideoRunOptions& options) {
  refuseAbsurdDuration(scene, options.maxFrames, options.maxFramesOption);
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = options.cancel;
  render::RenderSettings settings = scene.render.pictureFor(scene::RenderSpec::Output::Video);
  settings.reuseStaticBackground = options.reuseStaticBackground;
  // llvmpipe does not check its allocations: short of memory, it crashes or hangs rather than
  // failing; an encoder fails mid-clip without saying why. So what both need is checked first.
  const std::uint64_t frameBytes =
      4 * static_cast<std::uint64_t>(settings.width) * static_cast<std::uint64_t>(settings.height);
  requireRendererAddressSpace(settings, sink.workingMemory(frameBytes));
  render::Renderer renderer(settings);
  ClipRecord clip = recordClip(scene, simulation, options.maxFrames, options.maxFramesOption);
  const ClipPlan plan = planOf(scene, clip);
  const RunRecord& record = clip.record;
  const std::vector<FrameState>& frames = record.frames;
  const long simulatedFrames = plan.simulatedFrames;
  const long total = plan.frames();

  VideoRunResult result;
  result.simulatedSeconds = plan.endTime;
  result.stopDescription = plan.stopDescription;
  const FrameRange range = framesIn(plan, options.window);
  const auto written = [&](long k) { return k >= range.first && k <= range.last; };
  const long toWrite = range.last - range.first + 1;

  SnapshotMaker snapshots(scene, simulation.model, record);
  std::optional<ClipInset> inset;
  if (options.inset) {
    inset.emplace(plan, frames, range);
    snapshots.setInset(inset->plot());
  }
  image::Image frame;
  std::optional<SoundTrack> sound;
  // An impact that takes the energy of dropping the coin by its own radius knocks at full volume.
  const double impactScale = simulation.model.M * simulation.model.g * simulation.model.a;
  if (scene.render.audio) sound.emplace(*scene.render.audio, scene.render.fps, impactScale);
  auto nextImpact = record.impacts.begin();
  // The sound between frames k - 1 and k plays with frame k - 1: it is kept when that frame is.
  const auto soundSink = [&](long k) { return k > 0 && written(k - 1) ? &sink : nullptr; };
  const auto push = [&](long k, double simulatedTime, double playbackRate) {
    sink.push(frame);
    if (options.onFrameTiming) options.onFrameTiming({result.frames, k, simulatedTime, playbackRate});
    ++result.frames;
    if (options.onFrame) options.onFrame({result.frames, toWrite});
  };
  for (long k = 0; k < total; ++k) {
    if (options.cancel != nullptr && options.cancel->load()) throw Cancelled();
    if (k >= simulatedFrames) {  // the hold: the landing's picture again, in silence
      if (sound) sound->rest(k, soundSink(k));
      // Simulated time stands still here, so the overlay says so instead of the landing's playback rate;
      // a window by video time may start inside the hold, with no picture drawn yet.
      if (written(k) && ((k == simulatedFrames && scene.render.hud) || k == range.first || inset)) {
        if (inset) snapshots.markInset(inset->progress(k), inset->labels(k));
        renderer.draw(snapshots.makeSnapshot(frames.back(), {fmt::format("landed, held {:g} s", kLandingHoldSeconds)}),
                      frame);
      }
      if (written(k)) push(k, plan.endTime, 0.0);
      continue;
    }
    const FrameState& state = frames[static_cast<std::size_t>(k)];
    const double playbackRate = plan.playbackRates[static_cast<std::size_t>(k)];
    std::vector<std::string> speed;
    if (scene.render.hud) {
      const double slowdown = 1 / playbackRate;
      if (slowdown > 1 + 1e-9) speed.push_back(fmt::format("slow motion ×{:.3g}", slowdown));
      if (slowdown < 1 - 1e-9) speed.push_back(fmt::format("fast forward ×{:.3g}", 1 / slowdown));
    }
    // Synthesised for every frame, so the sound is the full render's; the trace catches up at the next snapshot.
    if (sound) {
      // The impacts since the previous frame knock in the block that ends at this one.
      for (; nextImpact != record.impacts.end() && nextImpact->t <= state.time; ++nextImpact) {
        const double previous = k > 0 ? frames[static_cast<std::size_t>(k - 1)].time : 0.0;
        const double span = state.time - previous;
        sound->knock(span > 0 ? (nextImpact->t - previous) / span : 1.0, nextImpact->energyLost);
      }
      sound->reachFrame(k, state.precessionRate, playbackRate, soundSink(k),
                        plan.landed && k + 1 == simulatedFrames);
    }
    if (!written(k)) continue;
    if (inset) snapshots.markInset(inset->progress(k), inset->labels(k));
    renderer.draw(snapshots.makeSnapshot(state, speed), frame);
    push(k, state.time, playbackRate);
  }
  if (sound) sound->finish(total, soundSink(total), plan.landed);
  sink.finish();
  return result;
}

}  // namespace coinroll::pipeline
