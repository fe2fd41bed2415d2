#include "pipeline/video_frames.h"

#include <fmt/format.h>

#include <cmath>
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

[[noreturn]] void refuseFrames(const scene::SceneConfig& scene, long maxFrames, const std::string& count) {
  throw std::invalid_argument(fmt::format(
      "render: duration {} s at time_scale {}, fps {}{} gives {} frames, more than the limit {}; shorten the duration, "
      "raise time_scale or lower fps, or raise the limit with --max-frames",
      scene.duration, scene.render.timeScale, scene.render.fps, scene.render.timeRemap ? " and the time remap" : "",
      count, maxFrames));
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
// t_(k+1) = t_k + playbackRate(rate(t_k)) / fps, up to the run's end.
class ClipPlan final : public FramePlan {
 public:
  ClipPlan(const scene::SceneConfig& scene, long maxFrames)
      : scene_(scene), maxFrames_(maxFrames), perFrame_(scene.render.timeScale / scene.render.fps),
        ofDuration_(frameCount(scene.duration, scene.render.timeScale, scene.render.fps)) {}

  std::optional<double> timeOf(long k, const RunSample* previous) override {
    if (!scene_.render.timeRemap) {
      // Past the limit frames are not recorded: the refusal needs the count to the run's end (recordFrames).
      if (k >= ofDuration_ || k >= maxFrames_) return std::nullopt;
      return static_cast<double>(k) * perFrame_;
    }
    if (k == 0) return 0.0;
    if (previous == nullptr) return std::nullopt;  // the run ended at frame k - 1
    const bool bySpin = scene_.render.timeRemap->rate == scene::TimeRemap::Rate::Spin;
    const double rate = std::abs(bySpin ? previous->forward.spinRate : previous->forward.precessionRate);
    return lastTime_ += playbackRate(scene_.render, rate) / scene_.render.fps;
  }

  bool keeps(long k, double time, double end) override {
    if (!scene_.render.timeRemap) return k < frameCount(end, scene_.render.timeScale, scene_.render.fps);
    // The sum of steps drifts by round-off; a relative 1e-12 keeps the frame at the very end.
    if (time > end * (1 + 1e-12)) return false;
    if (k == maxFrames_) {
      refuseFrames(scene_, maxFrames_,
                   fmt::format("more than {} (the time remap slows it at t = {:.6g} s)", maxFrames_, time));
    }
    return true;
  }

 private:
  const scene::SceneConfig& scene_;
  long maxFrames_;
  double perFrame_;    // s of simulated time, without a remap
  long ofDuration_;    // frames of a run that lasts its duration, without a remap
  double lastTime_ = 0;  // s, the remapped frame time last given
};

}  // namespace

RunRecord recordFrames(const scene::SceneConfig& scene, const Simulation& simulation, long maxFrames) {
  ClipPlan plan(scene, maxFrames);
  RunRecord record = recordRun(simulation, plan);
  if (!scene.render.timeRemap) {
    if (const long total = frameCount(record.survey.endTime, scene.render.timeScale, scene.render.fps);
        total > maxFrames) {
      refuseFrames(scene, maxFrames, std::to_string(total));
    }
  }
  return record;
}

namespace {

// The sound track, produced frame by frame from the states the pictures use: the block between
// frames k - 1 and k is synthesised when frame k's state is known, its pitch moving linearly
// between the two frames' (docs/sound.md §2).
class SoundTrack {
 public:
  SoundTrack(const scene::AudioSpec& spec, int fps) : spec_(spec), fps_(fps), synth_(spec, video::kAudioSampleRate) {}

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
    if (k == 1) synth_.fadeIn(block_);
    if (last) synth_.fadeOut(block_);
    if (sink != nullptr) sink->pushAudio(block_);
  }

  scene::AudioSpec spec_;
  int fps_;
  CoinSound synth_;
  double frequency_ = 0;  // Hz, at the previous frame
  std::vector<float> block_;
};

}  // namespace

VideoRunResult renderVideo(const scene::SceneConfig& scene, video::FrameSink& sink, const VideoRunOptions& options) {
  // The duration's frames bound what a run that goes the distance shows (a remap only adds):
  // absurd ones are refused before the pass over the run (video_frames.h, kUpFrontFrameFactor).
  if (const double atMost = static_cast<double>(scene.duration) / scene.render.timeScale * scene.render.fps;
      atMost > kUpFrontFrameFactor * static_cast<double>(options.maxFrames)) {
    refuseFrames(scene, options.maxFrames, fmt::format("{:.4g}", atMost));
  }
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = options.cancel;
  render::RenderSettings settings = scene.render.picture;
  settings.reuseStaticBackground = options.reuseStaticBackground;
  // llvmpipe does not check its allocations: short of memory, it crashes or hangs rather than
  // failing; an encoder fails mid-clip without saying why. So what both need is checked first.
  const std::uint64_t frameBytes =
      4 * static_cast<std::uint64_t>(settings.width) * static_cast<std::uint64_t>(settings.height);
  requireRendererAddressSpace(settings, sink.workingMemory(frameBytes));
  render::Renderer renderer(settings);
  RunRecord record = recordFrames(scene, simulation, options.maxFrames);
  const MotionSurvey& survey = record.survey;
  std::vector<FrameState>& frames = record.frames;

  VideoRunResult result;
  result.simulatedSeconds = survey.endTime;
  if (survey.stoppedBy) result.stopDescription = describeStop(*survey.stoppedBy);
  // A coin that landed on its face is shown at its landing, then lies still for a while before the
  // clip ends, so the end is seen.
  const bool landed = survey.stoppedBy && survey.stoppedBy->event == physics::ModelEvent::FaceDown;
  const bool landingFrameAdded = landed && frames.back().time < survey.endTime;
  if (landingFrameAdded) frames.push_back(record.end);
  const long simulatedFrames = static_cast<long>(frames.size());
  const long holdFrames = landed ? std::lround(kLandingHoldSeconds * scene.render.fps) : 0;
  const long total = simulatedFrames + holdFrames;

  // Frame k's simulated time: the hold repeats the landing, at the run's end.
  const auto timeOf = [&](long k) {
    return k < simulatedFrames ? frames[static_cast<std::size_t>(k)].time : survey.endTime;
  };
  const TimeWindow& window = options.window;
  const auto written = [&](long k) {
    const double t = timeOf(k);
    return t >= window.from - kWindowTolerance && t <= window.to + kWindowTolerance;
  };
  long toWrite = 0;
  for (long k = 0; k < total; ++k) toWrite += written(k) ? 1 : 0;
  if (toWrite == 0) {
    if (window.from > survey.endTime + kWindowTolerance) {
      throw std::invalid_argument(fmt::format(
          "--from {}: beyond the run's end at {:.9g} s{}; give a time in [0, {:.9g}]", window.from, survey.endTime,
          survey.stoppedBy ? " (" + describeStop(*survey.stoppedBy) + ")" : "", survey.endTime));
    }
    throw std::invalid_argument(
        fmt::format("--from {} --to {}: no frame's simulated time lies in this window (frames are "
                    "{:.6g} s of simulated time apart{}); widen it",
                    window.from, window.to, scene.render.timeScale / scene.render.fps,
                    scene.render.timeRemap ? ", less where render.time_remap slows them" : ""));
  }

  SnapshotMaker snapshots(scene, simulation.model, record);
  image::Image frame;
  std::optional<SoundTrack> sound;
  if (scene.render.audio) sound.emplace(*scene.render.audio, scene.render.fps);
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
      // Simulated time stands still here, so the overlay says so instead of the landing's playback rate.
      if (k == simulatedFrames && scene.render.hud && written(k)) {
        renderer.draw(snapshots.makeSnapshot(frames.back(), {fmt::format("landed, held {:g} s", kLandingHoldSeconds)}),
                      frame);
      }
      if (written(k)) push(k, survey.endTime, 0.0);
      continue;
    }
    const FrameState& state = frames[static_cast<std::size_t>(k)];
    const double t = state.time;
    // Simulated seconds per video second at this frame, from the frame times. The clip's last planned
    // frame and an added landing frame keep the pace of the frame before (a remapped clip's end is
    // still in slow motion), not that of the short step to the landing.
    const auto index = static_cast<std::size_t>(k);
    const std::size_t lastPlanned = frames.size() - (landingFrameAdded ? 2 : 1);
    const double step = index < lastPlanned ? frames[index + 1].time - t
                        : lastPlanned > 0   ? frames[lastPlanned].time - frames[lastPlanned - 1].time
                                            : scene.render.timeScale / scene.render.fps;
    const double playbackRate = step * scene.render.fps;
    std::vector<std::string> speed;
    if (scene.render.hud) {
      const double slowdown = 1 / playbackRate;
      if (slowdown > 1 + 1e-9) speed.push_back(fmt::format("slow motion ×{:.3g}", slowdown));
      if (slowdown < 1 - 1e-9) speed.push_back(fmt::format("fast forward ×{:.3g}", 1 / slowdown));
    }
    // Synthesised for every frame, so the sound is the full render's; the trace catches up at the next snapshot.
    if (sound)
      sound->reachFrame(k, state.precessionRate, playbackRate, soundSink(k), landed && k + 1 == simulatedFrames);
    if (!written(k)) continue;
    renderer.draw(snapshots.makeSnapshot(state, speed), frame);
    push(k, t, playbackRate);
  }
  if (sound) sound->finish(total, soundSink(total), landed);
  sink.finish();
  return result;
}

}  // namespace coinroll::pipeline
