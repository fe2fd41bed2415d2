#pragma once
// A scene as the program uses it: validated, defaults filled in, SI units and radians
// (the file's degrees are converted once, in scene_loader.cpp). Field names follow the JSON keys
// of INTERFACE.md; README "Scene format" lists each with unit and default.

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "physics/effects.h"
#include "physics/formulation.h"

namespace coinroll::scene {

enum class Shape { Disk, Ring, Custom };

struct CoinSpec {
  Shape shape = Shape::Disk;
  double radius = 0;       // m, required, > 0
  double mass = 0;         // kg, required, > 0
  double innerRadius = 0;  // m, ring only: hole radius b in [0, radius]; default radius (thin hoop)
  double thickness = 0;    // m, rendering only, > 0; default 0.06 * radius
  std::optional<double> I_X, I_Z;  // kg m^2, custom only (required there)
};

struct ExplicitInitial {
  double theta = 0, phi = 0, psi = 0;              // rad (degrees in the file)
  double omega_X = 0, omega_Y = 0, omega_Z = 0;    // rad/s
  double x = 0, z = 0;                             // m
};

enum class SteadyKind { Straight, Circle, SpinInPlace };

struct SteadyInitial {
  SteadyKind kind = SteadyKind::Straight;
  double theta = 0;    // rad; circle and spin-in-place
  double omega_Z = 0;  // rad/s; straight and circle
  int branch = +1;     // circle: +1 for the f+ root, -1 for f-
  double phi = 0, psi = 0, x = 0, z = 0;  // rad, rad, m, m
};

using InitialSpec = std::variant<ExplicitInitial, SteadyInitial>;

using physics::Formulation;

struct SolverSpec {
  // README "Formulations": the Euler angles are the more accurate per unit of time on every
  // example; the quaternion is for runs that must go nearer flat than 89 degrees.
  Formulation formulation = Formulation::EulerAngles;
  std::string method = "dop853";
  double rtol = 1e-10;  // adaptive methods
  double atol = 1e-12;  // adaptive methods
  double dt = 1e-3;     // s, fixed-step methods
};

struct CameraSpec {
  std::string mode = "fixed";  // fixed | orbit | follow
  std::optional<std::array<double, 3>> eye, target;  // m; absent = framed from the motion
  double fovDegrees = 35;        // vertical field of view
  double orbitPeriod = 10;       // s of simulated time per revolution (orbit)
  double elevationDegrees = 30;  // camera elevation above the floor for automatic framing
};

struct VideoSpec {
  int crf = 18;                    // x264 constant rate factor, 0..51
  std::string preset = "veryfast"; // x264 preset
  // x264 threads, fixed so the bytes are reproducible. One: the renderer already keeps both cores
  // of the reference machine busy, and a second encoder thread only competes with it
  // (bench/pipeline_bench: 8.85 s vs 9.04 s end to end for the orbiting 10 s clip).
  int threads = 1;
};

// render.time_remap: which rate drives the slow motion.
struct TimeRemap {
  enum class Rate {
    Spin,        // spin_rate: |psi-dot|, the rim rolling over the floor
    Precession,  // precession_rate: |phi-dot| = Omega, the contact point going round the floor
  };
  Rate rate = Rate::Precession;
  double limit = 0;  // rad/s, > 0
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

struct RenderSpec {
  int width = 1280, height = 720;  // pixels, even
  int fps = 30;                    // frames per second of video
  std::string antialiasing = "msaa";  // msaa (render.msaa samples per pixel) | fxaa (one sample, then FXAA)
  int msaa = 4;                    // samples per pixel: 1, 2, 4 or 8
  double timeScale = 1.0;          // video seconds per simulated second
  // When set, playback slows further whenever the chosen rate exceeds its limit, so that rate seen
  // on screen never exceeds the limit times time_scale (an Euler's disk stays readable).
  std::optional<TimeRemap> timeRemap;
  CameraSpec camera;
  bool trace = true, hud = true;
  VideoSpec video;
  std::optional<AudioSpec> audio;  // absent: no sound track
};

// What the validity events lift-off and slip do (INTERFACE.md "Dissipation").
enum class OnInvalid {
  Stop,  // end the run at the event
  Warn,  // report each crossing with its time and go on
};

struct SceneConfig {
  std::string name = "coinroll";
  CoinSpec coin;
  double gravity = 9.81;            // m/s^2
  std::optional<double> friction;   // static friction coefficient mu; absent = no slip monitor
  InitialSpec initial;
  double duration = 0;              // s, required
  SolverSpec solver;
  std::vector<physics::Effect> effects;  // empty: the seed's ideal rolling
  OnInvalid onInvalid = OnInvalid::Stop;
  RenderSpec render;
};

}  // namespace coinroll::scene
