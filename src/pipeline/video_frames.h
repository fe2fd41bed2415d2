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
#include <vector>

#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "scene/scene_config.h"
#include "pipeline/cancelled.h"
#include "video/frame_sink.h"

namespace coinroll::pipeline {

// Frames above this need --max-frames: 1 000 000 frames is 9 h of video at 30 fps, and a typo in
// a duration or a time remap should be refused before hours of work, not after. The frames a
// clip shows are known once the pass over the run has found where it ends (an event may end it
// long before its duration); before that pass only a duration that alone would give
// kUpFrontFrameFactor times the limit is refused, since the pass alone could take hours.
inline constexpr long kDefaultMaxFrames = 1'000'000;
inline constexpr double kUpFrontFrameFactor = 1000;

// s of video. A clip whose coin lands on its face (event face-down) holds the landing's picture
// this long after its last simulated frame, in silence.
inline constexpr double kLandingHoldSeconds = 1.5;

// Frames in a clip of `simulatedSeconds` at `fps` and `timeScale`: k = 0 .. floor(video length * fps).
long frameCount(double simulatedSeconds, double timeScale, int fps);

// Simulated seconds per video second at a moment whose remapped rate (|psi-dot| or |phi-dot|, per
// render.time_remap) is `rate`. Without a remap it is time_scale. With a remap of limit S and
// growth g the picture shows the rate at
//   v = max(time_scale S, min(time_scale S (rate / S)^g, pi fps / 2))   rad per video second
// once rate > S, so the playback rate is min(time_scale, v / rate). g = 0 holds the visible rate at
// time_scale S (the remap's original rule); g > 0 lets it grow with the real rate, slower than it,
// so an Euler's disk's whirl is seen to speed up, up to a quarter turn per frame, beyond which a
// turning marker would alias (a half turn per frame is the Nyquist limit).
double playbackRate(const scene::RenderSpec& render, double rate);

// The one pass over `simulation` (buildSimulation(scene)): the survey, the trace and the state at
// every frame time t_(k+1) = t_k + playbackRate(rate(t_k)) / fps up to the run's end. Throws
// std::invalid_argument when the clip has more than `maxFrames` frames.
RunRecord recordFrames(const scene::SceneConfig& scene, const Simulation& simulation,
                       long maxFrames = kDefaultMaxFrames);

struct FrameProgress {
  long frame = 0;  // frames done
  long total = 0;
};

// A frame as written (render --frame-times): where it lies in the output and in the whole clip,
// and the time it shows.
struct FrameTiming {
  long frame = 0;             // index in the output, from 0: it plays at video time frame / fps
  long clipFrame = 0;         // index in the full render (differs from `frame` inside a --from/--to window)
  double simulatedTime = 0;   // s, the simulated time shown
  // Simulated s per video s at this frame, as the overlay and the sound's pitch use it: the step to
  // the next frame times fps (the last simulated frames keep the pace before; 0 in a landing's hold).
  double playbackRate = 0;
};

// The frames a render writes: those whose simulated time lies in [from, to] (within
// kWindowTolerance), exactly as the full render draws them. `to` past the run's end means the end.
struct TimeWindow {
  double from = 0;                                      // s of simulated time
  double to = std::numeric_limits<double>::infinity();  // s of simulated time
};
inline constexpr double kWindowTolerance = 1e-9;  // s: a frame time computed as a sum may miss a bound by round-off

struct VideoRunOptions {
  std::function<void(const FrameProgress&)> onFrame = {};  // called after each frame; may be empty
  std::function<void(const FrameTiming&)> onFrameTiming = {};  // called for each frame pushed, in order; may be empty
  const std::atomic<bool>* cancel = nullptr;          // when set and true, the loop stops (Cancelled)
  long maxFrames = kDefaultMaxFrames;                 // more frames: std::invalid_argument, before any work
  bool reuseStaticBackground = true;  // render::RenderSettings; off only to measure what it saves
  // Frames outside it are neither drawn nor pushed (the simulation and the trace still run from 0),
  // nor is their sound. std::invalid_argument naming --from and --to when no frame lies in it.
  TimeWindow window = {};
};

struct VideoRunResult {
  long frames = 0;  // frames written
  double simulatedSeconds = 0;  // s shown; less than the duration when a validity event ended the run
  std::optional<std::string> stopDescription;
};

// Renders every frame of `scene` into `sink` and finishes it. Throws scene::SceneError for
// scenes only physics can judge, std::invalid_argument for render settings the renderer refuses,
// Cancelled when asked to stop; the sink is then left unfinished (it removes its output).
VideoRunResult renderVideo(const scene::SceneConfig& scene, video::FrameSink& sink,
                           const VideoRunOptions& options = {});

}  // namespace coinroll::pipeline
