#pragma once
// The clip's clock: which simulated time each frame of a clip shows, and how many simulated seconds
// a second of video shows at each moment (render.time_scale, slowed by render.time_remap where the
// coin turns fast, flies or strikes the floor). `render` draws its frames at these times
// (video_frames.h), `render --plan` prints them, and the page plays its runs by them (the WebAssembly
// core's visual track, visual_track.h). Nothing here draws.

#include <atomic>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "pipeline/slow_motion.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// Frames above this need --max-frames: 1 000 000 frames is 9 h of video at 30 fps, and a typo in
// a duration or a time remap should be refused before hours of work, not after. The frames a
// clip shows are known once the pass over the run has found where it ends (an event may end it
// long before its duration); before that pass only a duration that alone would give
// kUpFrontFrameFactor times the limit is refused, since the pass alone could take hours.
inline constexpr long kDefaultMaxFrames = 1'000'000;
inline constexpr double kUpFrontFrameFactor = 1000;
inline constexpr std::string_view kMaxFramesOption = "--max-frames";

// The one pass over `simulation` (buildSimulation(scene)): the survey, the trace and the state at
// every frame time t_(k+1) = t_k + playbackRate(rate(t_k)) / fps up to the run's end, or slower where
// render.time_remap.flight or .impact slows it (slow_motion.h: known from a first run before it). Throws
// std::invalid_argument when the clip has more than `maxFrames` frames.
RunRecord recordFrames(const scene::SceneConfig& scene, const Simulation& simulation,
                       long maxFrames = kDefaultMaxFrames);

// s of video. A clip whose coin lands on its face (event face-down) holds the landing's picture
// this long after its last simulated frame, in silence; the page holds its end as long.
inline constexpr double kLandingHoldSeconds = 1.5;

// Frames in a clip of `simulatedSeconds` at `fps` and `timeScale`: k = 0 .. floor(video length * fps).
long frameCount(double simulatedSeconds, double timeScale, int fps);

// Whether a rule of render.time_remap may slow the clip: frame times are then summed step by step.
bool isRemapped(const scene::RenderSpec& render);

// Simulated seconds per video second at a moment whose remapped rate (|psi-dot| or |phi-dot|, per
// render.time_remap) is `rate`. Without a remap it is time_scale. With a remap of limit S and
// growth g the picture shows the rate at
//   v = max(time_scale S, min(time_scale S (rate / S)^g, pi fps / 2))   rad per video second
// once rate > S, so the playback rate is min(time_scale, v / rate). g = 0 holds the visible rate at
// time_scale S (the remap's original rule); g > 0 lets it grow with the real rate, slower than it,
// so an Euler's disk's whirl is seen to speed up, up to a quarter turn per frame, beyond which a
// turning marker would alias (a half turn per frame is the Nyquist limit).
double playbackRate(const scene::RenderSpec& render, double rate);

struct ClipRate {
  double rate = 1;  // simulated s per video s
  SlowedBy by = SlowedBy::Nothing;
};

// The playback rate at simulated time t with the coin spinning at `spinRate` (psi-dot) and its
// contact going round at `precessionRate` (phi-dot), rad/s: the slowest of the rate rule's and the
// flight and impact slow-downs' at t (from `schedule`, known ahead).
ClipRate clipRateAt(const scene::RenderSpec& render, const SlowMotionSchedule& schedule, double t, double spinRate,
                    double precessionRate);

// The clip a render draws, as the one pass over the run chose it, before anything is drawn: what
// `render --plan` prints and the frame loop then draws. Frame k plays at video time k / fps.
struct ClipPlan {
  int fps = 0;
  double timeScale = 1;       // render.time_scale: simulated s per video s without a remap
  bool remapped = false;      // render.time_remap is set: the playback rate follows the motion
  bool byEvents = false;      // render.time_remap.flight or .impact is set
  std::vector<double> times;  // s of simulated time shown by each frame; the landing's hold repeats endTime
  // Simulated s per video s at each frame, as the overlay and the sound's pitch use it (FrameTiming).
  std::vector<double> playbackRates;
  std::vector<double> contactRates;  // rad/s, |phi-dot| at each frame (the hold keeps the landing's)
  std::vector<SlowedBy> slowedBy;    // the time remap's rule that set each frame's playback rate
  // What render.time_remap.flight and .impact followed (slow_motion.h): empty without them.
  std::vector<SlowMotionSchedule::Span> flights;
  std::vector<double> impacts;  // s
  long simulatedFrames = 0;     // frames before the landing's hold
  bool landed = false;          // the coin landed on its face: kLandingHoldSeconds of hold follow
  double endTime = 0;           // s of simulated time where the run ends (its duration, or an event)
  std::optional<std::string> stopDescription;

  long frames() const { return static_cast<long>(times.size()); }
  // s: each frame lasts 1 / fps, so N frames play N / fps.
  double videoSeconds() const { return static_cast<double>(frames()) / fps; }
};

// The clip `renderVideo(scene, ...)` would draw, by the same pass over the run (nothing is drawn).
// Throws std::invalid_argument for more than `maxFrames` frames, Cancelled when `cancel` turns true.
ClipPlan planClip(const scene::SceneConfig& scene, long maxFrames = kDefaultMaxFrames,
                  const std::atomic<bool>* cancel = nullptr);

// The one pass's record and what the plan reports besides: the rule behind each frame's rate and
// the flight and impact schedule it followed.
struct ClipRecord {
  RunRecord record;
  std::vector<SlowedBy> slowedBy;
  SlowMotionSchedule schedule;
};

// recordFrames's pass, with what the plan reports besides; refusals name `maxFramesOption`.
ClipRecord recordClip(const scene::SceneConfig& scene, const Simulation& simulation, long maxFrames,
                      std::string_view maxFramesOption);

// The up-front refusal: the duration's frames bound what a run that goes the distance shows (a remap
// only adds), so absurd ones are refused before the pass over the run (kUpFrontFrameFactor).
void refuseAbsurdDuration(const scene::SceneConfig& scene, long maxFrames, std::string_view maxFramesOption);

// The plan of the frames `clip` holds; a coin that landed on its face gets its landing's frame
// (appended to clip.record.frames) and then lies still for kLandingHoldSeconds, so the end is seen.
ClipPlan planOf(const scene::SceneConfig& scene, ClipRecord& clip);

}  // namespace coinroll::pipeline
