#include "pipeline/video_frames.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/clip_inset.h"
#include "pipeline/clip_window.h"
#include "pipeline/motion_survey.h"
#include "pipeline/playback_clock.h"
#include "pipeline/run_record.h"
#include "pipeline/resources.h"
#include "pipeline/plan_report.h"
#include "pipeline/simulation.h"
#include "pipeline/slow_motion.h"
#include "pipeline/snapshot.h"
#include "pipeline/sound_track.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

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
      sound->reachFrame(k, state.precessionRate, playbackRate, soundSink(k), plan.landed && k + 1 == simulatedFrames);
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
