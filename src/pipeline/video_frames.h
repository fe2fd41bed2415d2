#pragma once
// The frame loop of `coinroll render`: frame k shows simulated time t_k = k * time_scale / fps,
// read from the integrator's dense output (one streaming pass, no re-integration, no stepping
// at the frame rate), drawn by the renderer and pushed to a sink. Memory does not grow with the
// clip's length beyond the trace, which is capped (traceInterval).

#include <atomic>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/simulation.h"
#include "scene/scene_config.h"
#include "pipeline/cancelled.h"
#include "video/frame_sink.h"

namespace coinroll::pipeline {

// Frames above this need --max-frames: 1 000 000 frames is 9 h of video at 30 fps, and a typo in
// a duration or a time remap should be refused before hours of work, not after. The frames a
// clip shows are known once the first pass has found where the run ends (an event may end it
// long before its duration); before that pass only a duration that alone would give
// kUpFrontFrameFactor times the limit is refused, since its first pass alone could take hours.
inline constexpr long kDefaultMaxFrames = 1'000'000;
inline constexpr double kUpFrontFrameFactor = 1000;

// s of video. A clip whose coin lands on its face (event face-down) holds the landing's picture
// this long after its last simulated frame, in silence.
inline constexpr double kLandingHoldSeconds = 1.5;

// Frames in a clip of `simulatedSeconds` at `fps` and `timeScale`: k = 0 .. floor(video length * fps).
long frameCount(double simulatedSeconds, double timeScale, int fps);

// Simulated time of every frame up to `endTime`. Without a remap, t_k = k time_scale / fps.
// With render.time_remap.spin_rate S, each frame advances by (time_scale / fps) min(1, S / |psi-dot(t_k)|):
// the picture slows down while the coin spins faster than S; precession_rate does the same with
// phi-dot, the contact point's rate round the floor.
// Throws std::invalid_argument naming the render fields when there would be more than
// `maxFrames`; stops planning there, so memory stays bounded whatever the time remap.
std::vector<double> frameTimes(const scene::SceneConfig& scene, const Simulation& simulation, double endTime,
                               long maxFrames = kDefaultMaxFrames);

struct FrameProgress {
  long frame = 0;  // frames done
  long total = 0;
};

// The frames a render writes: those whose simulated time lies in [from, to] (within
// kWindowTolerance), exactly as the full render draws them. `to` past the run's end means the end.
struct TimeWindow {
  double from = 0;                                      // s of simulated time
  double to = std::numeric_limits<double>::infinity();  // s of simulated time
};
inline constexpr double kWindowTolerance = 1e-9;  // s: a frame time computed as a sum may miss a bound by round-off

struct VideoRunOptions {
  std::function<void(const FrameProgress&)> onFrame;  // called after each frame; may be empty
  const std::atomic<bool>* cancel = nullptr;          // when set and true, the loop stops (Cancelled)
  long maxFrames = kDefaultMaxFrames;                 // more frames: std::invalid_argument, before any work
  bool reuseStaticBackground = true;  // render::RenderSettings; off only to measure what it saves
  // Frames outside it are neither drawn nor pushed (the simulation and the trace still run from 0),
  // nor is their sound. std::invalid_argument naming --from and --to when no frame lies in it.
  TimeWindow window;
};

struct VideoRunResult {
  long frames = 0;  // frames written
  double simulatedSeconds = 0;  // s shown; less than the duration when a validity event ended the run
  std::optional<std::string> stopDescription;
};

// Renders every frame of `scene` into `sink` and finishes it. Throws scene::SceneError for
// scenes only physics can judge, std::invalid_argument for render settings the renderer refuses,
// Cancelled when asked to stop; the sink is then left unfinished (it removes its output).
VideoRunResult renderVideo(const scene::SceneConfig& scene, video::FrameSink& sink, const VideoRunOptions& options = {});

}  // namespace coinroll::pipeline
