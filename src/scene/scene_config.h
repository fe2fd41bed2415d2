#pragma once
// A scene as the program uses it: validated, defaults filled in, SI units and radians
// (the file's degrees are converted once, in scene_loader.cpp). Field names follow the JSON keys
// of docs/contract.md; docs/scene.md lists each with unit and default (scene_schema.cpp). What the renderer and
// the encoder are built with is held in their own types (render/render_settings.h,
// video/video_options.h), whose defaults and limits are the scene's: defined there, once.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "integrate/solver_config.h"
#include "physics/effects.h"
#include "physics/formulation.h"
#include "render/render_settings.h"
#include "video/video_options.h"

namespace coinroll::scene {

enum class Shape { Disk, Ring, Custom };

struct CoinSpec {
  Shape shape = Shape::Disk;
  double radius = 0;       // m, required, > 0
  double mass = 0;         // kg, required, > 0
  double innerRadius = 0;  // m, ring only: hole radius b in [0, radius]; default radius (thin hoop)
  // m, coin.thickness: when given the coin is a solid of that thickness in the dynamics (docs/contract.md
  // "The coin's rim"); absent, the seed's thin coin (drawn 0.06 radius thick, in RenderSpec::picture).
  std::optional<double> thickness;
  double edgeRadius = 0;  // m, coin.edge_radius rho in [0, min(h/2, radius - inner radius)]; default h/2 (capped)
  std::optional<double> I_X, I_Z;  // kg m^2, custom only (required there)
};

struct ExplicitInitial {
  double theta = 0, phi = 0, psi = 0;            // rad (degrees in the file)
  double omega_X = 0, omega_Y = 0, omega_Z = 0;  // rad/s
  double x = 0, z = 0;                           // m
  // m/s, initial.v_x and v_z (only with "sliding": true): the centre's velocity; absent, the rolling one.
  std::optional<std::array<double, 2>> velocity;
  // Only with "flight": true. m, initial.y: the centre's height (absent: resting on the floor);
  // m/s, initial.v_y: its vertical velocity.
  std::optional<double> y, v_y;
};

enum class SteadyKind { Straight, Circle, SpinInPlace };

struct SteadyInitial {
  SteadyKind kind = SteadyKind::Straight;
  double theta = 0;                       // rad; circle and spin-in-place
  double omega_Z = 0;                     // rad/s; straight and circle
  int branch = +1;                        // circle: +1 for the f+ root, -1 for f-
  double phi = 0, psi = 0, x = 0, z = 0;  // rad, rad, m, m
};

using InitialSpec = std::variant<ExplicitInitial, SteadyInitial>;

using physics::Formulation;

struct SolverSpec {
  // docs/physics.md "Formulations": the Euler angles are the more accurate per unit of time on every
  // example; the quaternion is for runs that must go nearer flat than 89 degrees. Absent: the Euler
  // angles, except for a coin with thickness and effects, whose landing only the quaternion reaches.
  std::optional<Formulation> formulation;
  // The integrator's own defaults (integrate/solver_config.h), its ranges beside them.
  integrate::Method method = integrate::SolverConfig{}.method;
  double rtol = integrate::SolverConfig{}.rtol;  // adaptive methods, [kMinRtol, kMaxRtol]
  double atol = integrate::SolverConfig{}.atol;  // adaptive methods, (0, kMaxAtol]
  double dt = integrate::SolverConfig{}.dt;      // s, fixed-step methods, [kMinDt, kMaxDt]
};

enum class CameraMode {
  Fixed,   // frames the whole motion from one place
  Orbit,   // circles the motion once per orbit period
  Follow,  // keeps the coin in the middle at a fixed offset
};

struct CameraSpec {
  CameraMode mode = CameraMode::Fixed;
  std::optional<std::array<double, 3>> eye, target;  // m; absent = framed from the motion
  double fovDegrees = render::kDefaultFovYDegrees;   // vertical field of view
  double orbitPeriod = 10;                           // s of simulated time per revolution (orbit)
  double elevationDegrees = 30;                      // camera elevation above the floor for automatic framing
};

// render.time_remap: which rate drives the slow motion.
struct TimeRemap {
  enum class Rate {
    Spin,        // spin_rate: |psi-dot|, the rim rolling over the floor
    Precession,  // precession_rate: |phi-dot| = Omega, the contact point going round the floor
  };
  Rate rate = Rate::Precession;
  double limit = 0;   // rad/s, > 0
  double growth = 0;  // in [0, 1): the visible rate grows as (rate / limit)^growth (video_frames.h)
};

// render.time_remap.flight and render.time_remap.impact: slow motion while the coin is in the air and
// around each impact of its rim ("flight": true), eased in and out (pipeline/video_frames.h eventSlowDown).
struct EventSlowDown {
  double slow = 1;  // in (0, 1]: time_scale's multiplier in the air, or at the impact's instant
  // s of simulated time over which the multiplier eases back to 1 on either side. The rate then changes
  // by at most a factor exp(1.5 (1 - slow) time_scale / (window fps)) from one frame to the next
  // (slow_motion.h): 1.27 at time_scale 1 and 60 fps for 0.1 s, which plays a toss's ease in 0.4 s.
  double window = 0.1;
};

// render.audio: a sound track synthesised from the motion (docs/sound.md).
struct AudioSpec {
  enum class Pitch {
    Video,  // the sound follows the video's clock: slow motion lowers the pitch by its factor
    Real,   // the pitch of the real motion, whatever the playback speed
  };
  enum class Timbre {
    Clicks,  // a band-limited click per turn of the contact point: the rim's rattle, a buzz when fast
    Tone,    // a pure sine at the contact point's rate
  };
  Pitch pitch = Pitch::Video;
  Timbre timbre = Timbre::Clicks;
  double frequencyScale = 1;  // k: the fundamental is k Omega / (2 pi); 1 is the physical rate
  double volume = 0.5;        // peak amplitude, (0, 1]
};

inline constexpr int kMaxFps = 240;  // render.fps in [1, kMaxFps]

struct RenderSpec {
  // What the Renderer is built with: render.width and height (even, for H.264's yuv420p),
  // render.antialiasing and msaa, and the coin as drawn (coin.thickness; a ring's hole narrowed
  // so a thin hoop still shows as a band). Drawn through pictureFor, which resolves "auto".
  render::RenderSettings picture = [] {
    render::RenderSettings settings;
    settings.antialiasing = render::Antialiasing::Auto;
    return settings;
  }();
  int fps = video::VideoOptions{}.fps;  // frames per second of video, 1..kMaxFps; the encoder's default
  double timeScale = 1.0;               // video seconds per simulated second
  // When set, playback slows further whenever the chosen rate exceeds its limit, so that rate seen
  // on screen never exceeds the limit times time_scale (an Euler's disk stays readable).
  std::optional<TimeRemap> timeRemap;
  // render.time_remap.flight and .impact: slower still in the air and near each impact, known from a
  // first run of the simulation (pipeline/video_frames.h); the slowest of all the rules plays.
  std::optional<EventSlowDown> flightSlowDown, impactSlowDown;
  CameraSpec camera;
  bool trace = true, hud = true;
  video::X264Options video;        // render.video
  std::optional<AudioSpec> audio;  // absent: no sound track
  // render.provenance: outputs name coinroll, its release and the scene's digest (docs/outputs.md).
  bool provenance = true;

  // What `picture` is drawn with for `output`: render.antialiasing "auto" made a method, from the
  // measurements of bench/antialias_quality (docs/quality.md "Anti-aliasing"):
  // - a still: ssaa with render.msaa samples per drawn pixel (16 a pixel at the default 4), a third
  //   of 4x MSAA's edge error for one picture's time; msaa once the doubled picture would pass
  //   kMaxImageSide (its buffers would take gigabytes);
  // - a video from a fixed camera: ssaa with one sample, which costs what 4x MSAA does a frame
  //   (0.9-1.0x: the floor is drawn once per clip) for 0.4x its mean edge error;
  // - a video from a moving camera: msaa, since there the floor is shaded every frame, and ssaa at
  //   four times the pixels costs 1.2x 4x MSAA's time.
  enum class Output { Still, Video };
  render::RenderSettings pictureFor(Output output) const {
    render::RenderSettings settings = picture;
    if (settings.antialiasing != render::Antialiasing::Auto) return settings;
    const bool doubledFits =
        render::kSupersampleFactor * std::max(picture.width, picture.height) <= render::kMaxImageSide;
    settings.antialiasing = doubledFits ? render::Antialiasing::Ssaa : render::Antialiasing::Msaa;
    if (output == Output::Video && camera.mode != CameraMode::Fixed) settings.antialiasing = render::Antialiasing::Msaa;
    if (output == Output::Video && settings.antialiasing == render::Antialiasing::Ssaa) settings.msaa = 1;
    return settings;
  }

  // The encoder's options for these pictures: the same size and frame rate, render.video, and an
  // audio track when render.audio asks for one.
  video::VideoOptions mp4Options() const {
    return {.width = picture.width,
            .height = picture.height,
            .fps = fps,
            .x264 = video,
            .audio = audio.has_value(),
            .alpha = picture.transparentBackground,
            .provenance = {}};  // the command's to fill: it knows the release and the scene document
  }
};

// What the validity events lift-off and slip do (docs/contract.md §4).
enum class OnInvalid {
  Stop,  // end the run at the event
  Warn,  // report each crossing with its time and go on
};

struct SceneConfig {
  std::string name = "coinroll";
  CoinSpec coin;
  double gravity = 9.81;                 // m/s^2
  std::optional<double> friction;        // mu: the slip monitor's cone, and Coulomb's kinetic coefficient when sliding
  std::optional<double> frictionStatic;  // friction_static >= friction: the rolling cone; absent = friction
  bool sliding = false;  // "sliding": true, the coin slides instead of stopping at slip (needs friction)
  // "flight": true (needs sliding): lift-off goes on in flight, and the rim's impacts bounce (docs/flight.md).
  bool flight = false;
  double restitution = 0;                // e in [0, 1], required with flight
  std::optional<double> impactFriction;  // mu during impacts; absent = friction
  bool stopWhenDecided = false;          // flight: end once the face up can no longer change (docs/flight.md §5a)
  InitialSpec initial;
  double duration = 0;  // s, required
  SolverSpec solver;
  std::vector<physics::Effect> effects;  // empty: the seed's ideal rolling
  OnInvalid onInvalid = OnInvalid::Stop;
  RenderSpec render;
};

}  // namespace coinroll::scene
