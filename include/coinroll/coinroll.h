#pragma once
// coinroll's C++ API: load a scene, simulate it to the trajectory CSV's columns, render a still
// into memory or a video into a file, find a steady motion's stability, sweep a grid of scenes.
// The same scenes, numbers and pixels as the command line (`coinroll simulate`, `still`,
// `render`, `steady`, `sweep`); the scene format is docs/scene.md.
//
//   find_package(coinroll REQUIRED)            or   pkg-config --cflags --libs coinroll
//   target_link_libraries(app PRIVATE coinroll::coinroll)
//
// Errors are exceptions: SceneError (a std::invalid_argument) for a bad scene, ArgumentError (one
// too) for a bad argument of a call, std::invalid_argument for another bad request (the message
// names the field and the fix, as the command line's exit 2), std::runtime_error for a run or an
// output that fails. A failed render leaves no file behind. The calls keep the command's rules for
// what they write and how much: an output never replaces the scene file it was read from, and a
// run's size is refused before any work when it passes the command's limit.
//
// The long calls take a `cancel` flag (Ctrl-C, a closed window, a deadline): set it from another
// thread or a signal handler and the call stops at its next sample, frame or grid point, removes
// any partial output and throws Cancelled. A null flag never cancels.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

// The library is built with hidden visibility; everything declared here is its exported API.
#pragma GCC visibility push(default)

namespace coinroll {

// "0.1.0": the release this library is.
std::string version();

// A call stopped because its `cancel` flag was set.
class Cancelled : public std::runtime_error {
 public:
  Cancelled();
};

// A scene the loader refused: the message names the field, the rule and the value, as
// `coinroll simulate`'s exit-2 message does.
class SceneError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A bad argument of a call: what() names it as this header spells it ("sampleDt: must be ...").
// A binding whose users spell the argument otherwise (Python's sample_dt) gives them naming(its
// spelling), the same message with their name in each place this one stands.
class ArgumentError : public std::invalid_argument {
 public:
  // `around`: the message's text before, between and after the places the argument is named.
  ArgumentError(std::string argument, std::vector<std::string> around);
  const std::string& argument() const noexcept { return argument_; }
  std::string naming(std::string_view spelling) const;

 private:
  std::string argument_;
  std::vector<std::string> around_;
};

// A validated scene. Cheap to copy (the scene is shared and never changes).
class Scene {
 public:
  // `overrides` are the command line's --set, KEY.PATH=VALUE ("initial.theta=12").
  static Scene fromFile(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  static Scene fromJson(std::string_view json, const std::vector<std::string>& overrides = {});
  // The built-in default scene (what `coinroll render` draws without a scene file).
  static Scene builtInDefault(const std::vector<std::string>& overrides = {});

  std::string name() const;
  double duration() const;  // s of simulated time
  // The file fromFile read, which renderVideo never writes over; none for the other two.
  std::optional<std::filesystem::path> file() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit Scene(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
};

// Scene::fromFile under the name the command-line contract gives it (docs/contract.md §9).
Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

// How a run ended.
struct RunEnd {
  // "duration" when the run reached the scene's duration, else the validity event that stopped it
  // early ("coin-flat", "face-down", "lift-off", "slip", ...): the sweep's end column.
  std::string event;
  double time = 0;  // s
  // What `coinroll simulate` prints after "stopped early: " (the event, its time and tilt, what it
  // means); empty for "duration".
  std::string description;
};

// The trajectory CSV as columns: names[i] is the CSV's header field i, values[i] its column, one
// entry per sample t = k sampleDt (and the same doubles the CSV prints).
struct Columns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  RunEnd end;  // of the run that was sampled (simulate; a sweep's table leaves it empty)

  std::size_t rows() const { return values.empty() ? 0 : values.front().size(); }
  // The column named `name` ("t", "theta", "energy", ...); std::out_of_range naming it if absent.
  const std::vector<double>& operator[](std::string_view name) const;
  const std::vector<double>& column(std::string_view name) const { return (*this)[name]; }
};

// What simulate returns, under the contract's name for it.
using Trajectory = Columns;

// Integrates the scene and samples it every `sampleDt` seconds (the CSV's --sample-dt). More than
// the command's limit of rows (floor(duration / sampleDt) + 1 > 1e8) is refused before any work with an
// ArgumentError naming sampleDt.
Columns simulate(const Scene& scene, double sampleDt = 0.01, const std::atomic<bool>* cancel = nullptr);

// An 8-bit RGBA picture, rows from the top, width * height * 4 bytes.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};

// The picture `coinroll still --time` draws at `time` seconds, in [0, duration] (clamped to where
// the run stopped, if a validity event ended it first). ArgumentError naming `time` outside it.
Image renderStill(const Scene& scene, double time, const std::atomic<bool>* cancel = nullptr);

// The clip `coinroll render -o output` writes; the kind follows the extension (.mp4 H.264, .gif,
// .webm VP9, .mov ProRes 4444, or a %d pattern for a PNG sequence). The file appears only once it
// is complete. Refused before any work, as the command refuses its -o, with an ArgumentError naming
// `output`: an empty name, or one that is (or whose frames would be) the scene's file() or a file of
// $COINROLL_ASSET_DIR or $COINROLL_SHADER_DIR; with std::invalid_argument naming the scene key: an
// output kind that cannot carry the scene's render settings (transparency in an .mp4).
void renderVideo(const Scene& scene, const std::filesystem::path& output, const std::atomic<bool>* cancel = nullptr);

// What `coinroll steady` prints: the steady motion the scene's `initial` names ({"steady":
// "straight" | "circle" | "spin-in-place", ...}; std::invalid_argument if it names none) and its
// linear stability. Small tilt perturbations obey d(theta)'' = -K d(theta) (docs/derivations.md
// eq. 3.6, docs/rim.md eq. 5.8 for a coin with a rim). These are the ideal model's: with effects
// the state is only where a slowing motion starts.
struct SteadyState {
  double mass = 0, radius = 0, gravity = 0;  // kg, m, m/s^2
  double inertiaX = 0, inertiaZ = 0;         // kg m^2
  double thickness = 0, edgeRadius = 0;      // m; 0 for a thin coin
  double naturalRate = 0;                    // rad/s, sqrt(g/a)
  // rad/s: below it straight rolling is unstable. None for a rim with corners, which cannot roll
  // upright (docs/rim.md eq. 5.4).
  std::optional<double> criticalSpin;
  // The state in the scene's units: angles in degrees, rates in rad/s, positions in m.
  double theta = 0, phi = 0, psi = 0, omega_X = 0, omega_Y = 0, omega_Z = 0, x = 0, z = 0;
  double precessionRate = 0, spinRate = 0;           // rad/s, phi-dot and psi-dot
  double centreOfMassRadius = 0, contactRadius = 0;  // m, of the circles traced; infinite rolling straight
  double normalForce = 0, frictionForce = 0;         // N, the floor's reaction
  double stiffness = 0;                              // K, 1/s^2
  std::string stability;                             // "stable" (K > 0), "unstable" (K < 0), "marginal"
};
SteadyState steady(const Scene& scene);

// What `coinroll sweep` writes: one summary row per point of the Cartesian grid of `axes`, each in
// the command's --grid syntax ("initial.theta=5:40:8", "coin.mass=0.01:1:5:log",
// "initial.omega_Z=8,12,16"; the last axis runs fastest), computed on `threads` threads (0: every
// hardware thread). A grid key that is no scene field, or no number, is refused before any work.
struct SweepTable {
  // "point", one column per axis (its key), then "t_end", "theta_min", "theta_max",
  // "energy_start", "energy_end", "theta_end" (rad, at the run's end: a toss's face, heads < 0);
  // NaN in those six where the point failed.
  Columns columns;
  std::vector<std::string> end;  // per point: "duration", the event that ended it, or "error: <why>"
  long gridPoints = 0;
  std::string digest;  // identifies the sweep (scene and axes) in its shards' rows
};
SweepTable sweep(const Scene& scene, const std::vector<std::string>& axes, int threads = 0,
                 const std::atomic<bool>* cancel = nullptr);

}  // namespace coinroll

#pragma GCC visibility pop
