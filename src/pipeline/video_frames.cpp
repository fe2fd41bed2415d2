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
#include "pipeline/playback_clock.h"
#include "pipeline/run_record.h"
#include "pipeline/resources.h"
#include "pipeline/simulation.h"
#include "pipeline/slow_motion.h"
#include "pipeline/snapshot.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

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

std::vector<std::string> overlayExtraLines(const ClipPlan& plan, long k) {
  // Simulated time stands still in the hold, so the overlay says so instead of the landing's playback rate.
  if (k >= plan.simulatedFrames) return {fmt::format("landed, held {:g} s", kLandingHoldSeconds)};
  const double slowdown = 1 / plan.playbackRates[static_cast<std::size_t>(k)];
  if (slowdown > 1 + 1e-9) return {fmt::format("slow motion ×{:.3g}", slowdown)};
  if (slowdown < 1 - 1e-9) return {fmt::format("fast forward ×{:.3g}", 1 / slowdown)};
  return {};
}

ClipViews planClipViews(const scene::SceneConfig& scene, long maxFrames, const std::atomic<bool>* cancel) {
  refuseAbsurdDuration(scene, maxFrames, kMaxFramesOption);
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = cancel;
  ClipRecord clip = recordClip(scene, simulation, maxFrames, kMaxFramesOption);
  ClipViews views{.plan = planOf(scene, clip), .frames = {}};
  const std::vector<FrameState>& frames = clip.record.frames;
  // renderVideo's snapshot maker, fed the same frames in the same order: the camera and the overlay
  // come from where render takes them, not from a second way of making them.
  SnapshotMaker snapshots(scene, simulation.model, clip.record);
  const long simulatedFrames = views.plan.simulatedFrames;
  views.frames.reserve(static_cast<std::size_t>(views.plan.frames()));
  for (long k = 0; k < views.plan.frames(); ++k) {
    if (cancel != nullptr && cancel->load()) throw Cancelled();
    // The hold shows the landing's frame again, as renderVideo draws it.
    const FrameState& state = frames[static_cast<std::size_t>(std::min(k, simulatedFrames - 1))];
    const render::FrameSnapshot& snapshot = snapshots.makeSnapshot(state, overlayExtraLines(views.plan, k));
    views.frames.push_back({snapshot.camera, snapshot.hudLines});
  }
  return views;
}

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
      // A window by video time may start inside the hold, with no picture drawn yet.
      if (written(k) && ((k == simulatedFrames && scene.render.hud) || k == range.first || inset)) {
        if (inset) snapshots.markInset(inset->progress(k), inset->labels(k));
        renderer.draw(snapshots.makeSnapshot(frames.back(), overlayExtraLines(plan, k)), frame);
      }
      if (written(k)) push(k, plan.endTime, 0.0);
      continue;
    }
    const FrameState& state = frames[static_cast<std::size_t>(k)];
    const double playbackRate = plan.playbackRates[static_cast<std::size_t>(k)];
    const std::vector<std::string> speed = scene.render.hud ? overlayExtraLines(plan, k) : std::vector<std::string>();
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
