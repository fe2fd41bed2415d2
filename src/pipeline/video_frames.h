#pragma once
// The frame loop of `coinroll render`: frame k shows simulated time t_k = k * time_scale / fps
// (or, with a time remap, t_(k+1) = t_k + playbackRate(rate(t_k)) / fps), read from the
// integrator's dense output (no stepping at the frame rate). The run is integrated once
// (run_record.h): one pass records the survey that places the camera, the trace and a compact
// state per frame (FrameState, 112 bytes); the loop then only draws. Memory grows with the frame
// count by those records alone (112 MB at kDefaultMaxFrames); the trace is capped (traceInterval).

#include <atomic>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/playback_clock.h"
#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "pipeline/slow_motion.h"
#include "scene/scene_config.h"
#include "pipeline/cancelled.h"
#include "pipeline/clip_window.h"
#include "render/frame_snapshot.h"
#include "video/frame_sink.h"

namespace coinroll::pipeline {

struct FrameProgress {
  long frame = 0;  // frames done
  long total = 0;
};

// A frame as written (render --frame-times): where it lies in the output and in the whole clip,
// and the time it shows.
struct FrameTiming {
  long frame = 0;            // index in the output, from 0: it plays at video time frame / fps
  long clipFrame = 0;        // index in the full render (differs from `frame` inside a --from/--to window)
  double simulatedTime = 0;  // s, the simulated time shown
  // Simulated s per video s at this frame, as the overlay and the sound's pitch use it: the step to
  // the next frame times fps (the last simulated frames keep the pace before; 0 in a landing's hold).
  double playbackRate = 0;
};

// What render draws a frame with besides the coin and the trace, as its snapshot holds it.
struct FrameView {
  render::CameraView camera;
  std::vector<std::string> overlayLines;  // none with render.hud off
};

// The clip `renderVideo(scene, ...)` would draw (planClip) and each of its frames' views, from the
// same pass over the run and the same snapshots, nothing drawn: what `render --plan --json` prints,
// so that another build of the renderer's code can be held against the program frame by frame.
struct ClipViews {
  ClipPlan plan;
  std::vector<FrameView> frames;  // one per frame of `plan`, the landing's hold included
};
ClipViews planClipViews(const scene::SceneConfig& scene, long maxFrames = kDefaultMaxFrames,
                        const std::atomic<bool>* cancel = nullptr);

struct VideoRunOptions {
  std::function<void(const FrameProgress&)> onFrame = {};      // called after each frame; may be empty
  std::function<void(const FrameTiming&)> onFrameTiming = {};  // called for each frame pushed, in order; may be empty
  const std::atomic<bool>* cancel = nullptr;                   // when set and true, the loop stops (Cancelled)
  long maxFrames = kDefaultMaxFrames;                          // more frames: std::invalid_argument, before any work
  // How the caller's user raises maxFrames, named in that refusal; empty when they cannot.
  std::string maxFramesOption = std::string(kMaxFramesOption);
  bool reuseStaticBackground = true;  // render::RenderSettings; off only to measure what it saves
  // Frames outside it are neither drawn nor pushed (the simulation and the trace still run from 0),
  // nor is their sound. std::invalid_argument naming its options when no frame lies in it (framesIn).
  TimeWindow window = {};
  // render --inset: a plot of the contact point's rate and the tilt over the whole clip in each
  // frame's corner, with a marker at the frame (a speed-up the slow motion hides reads off it).
  bool inset = false;
};

struct VideoRunResult {
  long frames = 0;              // frames written
  double simulatedSeconds = 0;  // s shown; less than the duration when a validity event ended the run
  std::optional<std::string> stopDescription;
};

// Renders every frame of `scene` into `sink` and finishes it. Throws scene::SceneError for
// scenes only physics can judge, std::invalid_argument for render settings the renderer refuses,
// Cancelled when asked to stop; the sink is then left unfinished (it removes its output).
VideoRunResult renderVideo(const scene::SceneConfig& scene, video::FrameSink& sink,
                           const VideoRunOptions& options = {});

}  // namespace coinroll::pipeline
