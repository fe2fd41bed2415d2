#include "scene/scene_schema.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <variant>

#include "integrate/solver_config.h"
#include "physics/effects.h"
#include "scene/scene_config.h"
#include "video/video_options.h"

namespace coinroll::scene::schema {

static_assert(namesEveryValue(Shape::Custom, kShapeNames));
static_assert(namesEveryValue(SteadyKind::SpinInPlace, kSteadyKindNames));
static_assert(namesEveryValue(OnInvalid::Warn, kOnInvalidNames));
static_assert(namesEveryValue(CameraMode::Follow, kCameraModeNames));
static_assert(namesEveryValue(AudioSpec::Pitch::Real, kPitchNames));
static_assert(namesEveryValue(AudioSpec::Timbre::Tone, kTimbreNames));
static_assert(std::variant_size_v<physics::Effect> == kEffectTypeNames.size());

namespace {

// Physical ranges: far wider than any coin, hoop or wheel, narrow enough that squares, products
// and exponentials of them stay finite in double precision. A value past them (a typo, 1e308)
// would otherwise reach the integrator as an infinite inertia or energy and fail there with a
// NaN step size instead of naming the field.
constexpr double kMinLength = 1e-6, kMaxLength = 1e3;  // m
constexpr double kMinMass = 1e-9, kMaxMass = 1e9;      // kg
constexpr double kMaxRate = 1e6;                       // rad/s
constexpr double kMaxSpeed = 1e3;                      // m/s, a launched coin; faster is a typo
constexpr double kMaxPosition = 1e6;                   // m
constexpr double kMaxGravity = 1e4;                    // m/s^2
// deg. Heading and spin angles mean the same modulo 360; past a million degrees a double's spacing
// grows towards the steps the integrator adds to them (at 1e20 the heading no longer moves).
constexpr double kMaxAngleDegrees = 1e6;
// kg m^2: what the mass and radius ranges allow for any body, with room for long bodies.
constexpr double kMinInertia = kMinMass * kMinLength * kMinLength, kMaxInertia = kMaxMass * kMaxLength * kMaxLength;

constexpr Bound open(double value) { return {value, false}; }
constexpr Bound closed(double value) { return {value, true}; }

// Presence conditions: `path` given; given with one of `values` (JSON text); one of `paths` given.
Condition given(std::string path) { return {.paths = {std::move(path)}}; }
Condition is(std::string path, std::vector<std::string> values) {
  return {.paths = {std::move(path)}, .values = std::move(values)};
}
Condition givenOneOf(std::vector<std::string> paths) { return {.paths = std::move(paths)}; }

// A default as JSON writes it, exponents without their padding zero: 1.8e-5, not 1.8e-05.
std::string number(double value) {
  std::string text = fmt::format("{}", value);
  if (const auto e = text.find("e-0"); e != std::string::npos) text.erase(e + 2, 1);
  if (const auto e = text.find("e+"); e != std::string::npos) text.erase(e + 1, 1);
  return text;
}
std::string jsonString(std::string_view text) { return fmt::format("\"{}\"", text); }
template <std::size_t N>
std::vector<std::string_view> namesOf(const std::array<std::string_view, N>& names) {
  return {names.begin(), names.end()};
}
template <class Enum, std::size_t N>
std::string nameOf(Enum value, const std::array<std::string_view, N>& names) {
  return jsonString(names[static_cast<std::size_t>(value)]);
}
// A power of ten as the solver's messages write it: 1e-3, 1e-14, 1.
std::string powerOfTen(double value) {
  if (value == 0) return "0";
  const int exponent = static_cast<int>(std::lround(std::log10(value)));
  return exponent == 0 ? fmt::format("{:g}", value)
                       : fmt::format("{:g}e{}", value / std::pow(10.0, exponent), exponent);
}

std::vector<Key> buildTable() {
  const SceneConfig scene;
  const CoinSpec coin;
  const SolverSpec solver;
  const RenderSpec render;
  const render::RenderSettings& picture = render.picture;
  const CameraSpec& camera = render.camera;
  const AudioSpec audio;
  const EventSlowDown slowDown;
  const physics::AirDrag air;
  const physics::RollingResistance rolling;
  const physics::SpinFriction pivoting;
  using T = Type;

  // A row's fields are packed as a table reads, not laid out one a line.
  // clang-format off
  std::vector<Key> table = {
      {.path = "name", .type = T::Text, .unit = "", .defaultText = jsonString(scene.name),
       .doc = "text; default output files are named after it"},
      {.path = "coin", .type = T::Object, .unit = "", .defaultText = "", .required = true,
       .presenceWhy = "an object with shape, radius, mass", .example = R"({"radius": 0.0375, "mass": 0.4})",
       .doc = "the body: its shape, size and mass"},
      {.path = "gravity", .type = T::Number, .unit = "m/s^2", .defaultText = number(scene.gravity),
       .lower = open(0), .upper = closed(kMaxGravity), .doc = "the acceleration of gravity"},
      {.path = "friction", .type = T::Number, .unit = "", .defaultText = "",
       .lower = closed(0), .example = "0.5",
       .doc = "mu, optional: the cone rolling must stay inside (the slip event), and Coulomb's "
                                  "kinetic coefficient with `sliding`; absent, no slip monitor"},
      {.path = "friction_static", .type = T::Number, .unit = "", .defaultText = "", .onlyWith = {given("friction")},
       .presenceWhy = "the kinetic coefficient, which it must be at least", .example = "0.6",
       .doc = "at least `friction` (its default): the cone |F| <= friction_static N that rolling stays inside "
              "(the slip event and the start-up check use it)"},
      {.path = "sliding", .type = T::Boolean, .unit = "", .defaultText = "false", .needs = {given("friction")},
       .presenceWhy = "the coefficient of Coulomb friction while the coin slides",
       .doc = "true: the coin slides with Coulomb friction instead of stopping at slip (needs `friction`)"},
      {.path = "flight", .type = T::Boolean, .unit = "", .defaultText = "false", .needs = {is("sliding", {"true"})},
       .presenceWhy = "a coin that lands rolls or slides again",
       .doc = "true: lift-off goes on in flight, the rim's impacts bounce and the coin rolls or slides again "
              "(docs/flight.md; needs `sliding` and `restitution`)"},
      {.path = "restitution", .type = T::Number, .unit = "", .defaultText = "", .required = true, .lower = closed(0),
       .upper = closed(1), .onlyWith = {is("flight", {"true"})},
       .presenceWhy = "the impacts of a flight bounce by it", .example = "0.5",
       .doc = "e, required with `flight`: an impact gives back e^2 of its compression's work (Stronge's energetic "
              "coefficient)"},
      {.path = "impact_friction", .type = T::Number, .unit = "", .defaultText = "", .lower = closed(0),
       .onlyWith = {is("flight", {"true"})}, .presenceWhy = "only a coin in flight has impacts", .example = "0.5",
       .doc = "mu during impacts; absent, `friction`"},
      {.path = "stop_when_decided", .type = T::Boolean, .unit = "", .defaultText = "false",
       .onlyWith = {is("flight", {"true"})}, .presenceWhy = "it ends a toss once its face up is final",
       .doc = "true: end the run (event `decided`) once the coin has less energy than standing upright on its rim "
              "takes, so its face up can no longer change; a sweep of tosses needs no more"},
      {.path = "initial", .type = T::Object, .unit = "", .defaultText = "", .required = true,
       .presenceWhy = "angles and rates, or a steady state",
       .example = R"({"steady": "circle", "theta": 20, "omega_Z": 10})",
       .doc = "the start: angles and rates, or a steady state (`initial[steady]`)"},
      {.path = "duration", .type = T::Number, .unit = "s", .defaultText = "", .required = true, .lower = open(0),
       .example = "1", .doc = "simulated time"},
      {.path = "solver", .type = T::Object, .unit = "", .defaultText = "{}",
       .doc = "the integrator and its tolerances"},
      {.path = "effects", .type = T::List, .unit = "", .defaultText = "[]",
       .doc = "dissipation laws, each at most once (`effects[air_drag]`, `effects[rolling_resistance]`, "
              "`effects[spin_friction]`); empty: the seed's ideal rolling, bit for bit"},
      {.path = "on_invalid", .type = T::Name, .unit = "", .defaultText = nameOf(scene.onInvalid, kOnInvalidNames),
       .names = namesOf(kOnInvalidNames),
       .doc = "`stop` ends the run at lift-off or slip; `warn` reports each crossing and goes on (with `sliding`, "
              "lift-off still ends the run)"},
      {.path = "render", .type = T::Object, .unit = "", .defaultText = "{}",
       .doc = "the picture, the video and the sound"},

      {.path = "coin.shape", .type = T::Name, .unit = "", .defaultText = nameOf(coin.shape, kShapeNames),
       .names = namesOf(kShapeNames),
       .doc = "`disk` (I_X = M a^2/4, I_Z = M a^2/2), `ring` (an annulus of hole radius `inner_radius` b: "
              "I_X = M (a^2 + b^2)/4, I_Z = M (a^2 + b^2)/2) or `custom` (`I_X` and `I_Z` given)"},
      {.path = "coin.radius", .type = T::Number, .unit = "m", .defaultText = "", .required = true,
       .lower = closed(kMinLength), .upper = closed(kMaxLength), .example = "0.0375", .doc = "a, the rim's radius"},
      {.path = "coin.mass", .type = T::Number, .unit = "kg", .defaultText = "", .required = true,
       .lower = closed(kMinMass), .upper = closed(kMaxMass), .example = "0.4", .doc = "M"},
      {.path = "coin.inner_radius", .type = T::Number, .unit = "m", .defaultText = "",
       .onlyWith = {is("coin.shape", {R"("ring")"})}, .presenceWhy = "only a ring has a hole", .example = "0.03",
       .doc = "b, the hole's radius, 0 <= b <= radius; default radius (a thin hoop)"},
      {.path = "coin.thickness", .type = T::Number, .unit = "m", .defaultText = "",
       .lower = closed(kMinLength * 0.06), .upper = closed(kMaxLength), .example = "0.003",
       .doc = "given, the coin is a solid of this thickness in the dynamics, not only in the picture (docs/rim.md); "
              "absent, the seed's thin coin, drawn 0.06 x radius thick"},
      {.path = "coin.edge_radius", .type = T::Number, .unit = "m", .defaultText = "",
       .onlyWith = {given("coin.thickness")}, .presenceWhy = "a thin coin has no rim to round", .example = "0.001",
       .doc = "the rim's rounding rho, 0 <= rho <= min(thickness / 2, radius - inner_radius); default the largest "
              "(a fully rounded rim); 0 is a sharp-cornered cylinder"},
      {.path = "coin.I_X", .type = T::Number, .unit = "kg m^2", .defaultText = "", .required = true,
       .lower = closed(kMinInertia), .upper = closed(kMaxInertia), .onlyWith = {is("coin.shape", {R"("custom")"})},
       .presenceWhy = "the other shapes fix the inertia", .example = "0.00014",
       .doc = "custom only, and required there: the moment about a diameter"},
      {.path = "coin.I_Z", .type = T::Number, .unit = "kg m^2", .defaultText = "", .required = true,
       .lower = closed(kMinInertia), .upper = closed(kMaxInertia), .onlyWith = {is("coin.shape", {R"("custom")"})},
       .presenceWhy = "the other shapes fix the inertia", .example = "0.00028",
       .doc = "custom only, and required there: the moment about the symmetry axis, at most 2 I_X"},

      {.path = "initial.theta", .type = T::Number, .unit = "degrees", .defaultText = "0", .lower = open(-90),
       .upper = open(90), .why = "the seed's equations are singular when the coin lies flat",
       .doc = "the tilt of the coin's face from upright"},
      {.path = "initial.phi", .type = T::Number, .unit = "deg", .defaultText = "0", .lower = closed(-kMaxAngleDegrees),
       .upper = closed(kMaxAngleDegrees), .why = "an angle is the same modulo 360; reduce it",
       .doc = "the heading of the rolling direction"},
      {.path = "initial.psi", .type = T::Number, .unit = "deg", .defaultText = "0", .lower = closed(-kMaxAngleDegrees),
       .upper = closed(kMaxAngleDegrees), .why = "an angle is the same modulo 360; reduce it",
       .doc = "the spin angle of the face"},
      {.path = "initial.omega_X", .type = T::Number, .unit = "rad/s", .defaultText = "0", .lower = closed(-kMaxRate),
       .upper = closed(kMaxRate), .doc = "the coin-frame rate about the horizontal diameter (the tilt's rate)"},
      {.path = "initial.omega_Y", .type = T::Number, .unit = "rad/s", .defaultText = "0", .lower = closed(-kMaxRate),
       .upper = closed(kMaxRate), .doc = "the coin-frame rate about the diameter through the contact point"},
      {.path = "initial.omega_Z", .type = T::Number, .unit = "rad/s", .defaultText = "0", .lower = closed(-kMaxRate),
       .upper = closed(kMaxRate), .doc = "the coin-frame rate about the symmetry axis (rolling)"},
      {.path = "initial.x", .type = T::Number, .unit = "m", .defaultText = "0", .lower = closed(-kMaxPosition),
       .upper = closed(kMaxPosition), .doc = "the centre of mass on the floor"},
      {.path = "initial.z", .type = T::Number, .unit = "m", .defaultText = "0", .lower = closed(-kMaxPosition),
       .upper = closed(kMaxPosition), .doc = "the centre of mass on the floor"},
      {.path = "initial.v_x", .type = T::Number, .unit = "m/s", .defaultText = "", .lower = closed(-kMaxSpeed),
       .upper = closed(kMaxSpeed), .onlyWith = {is("sliding", {"true"})},
       .presenceWhy = "a rolling coin's velocity follows from its rates", .example = "0.1",
       .doc = "the centre's velocity, a skidding launch; absent, the rolling velocity"},
      {.path = "initial.v_z", .type = T::Number, .unit = "m/s", .defaultText = "", .lower = closed(-kMaxSpeed),
       .upper = closed(kMaxSpeed), .onlyWith = {is("sliding", {"true"})},
       .presenceWhy = "a rolling coin's velocity follows from its rates", .example = "0.1",
       .doc = "the centre's velocity, a skidding launch; absent, the rolling velocity"},

      {.path = "initial.y", .type = T::Number, .unit = "m", .defaultText = "", .lower = closed(0),
       .upper = closed(kMaxPosition), .onlyWith = {is("flight", {"true"})},
       .presenceWhy = "a rolling or sliding coin's height and vertical velocity follow from its attitude and rates",
       .example = "0.1",
       .doc = "the centre's height: above resting on the rim, the coin starts in flight; absent, on the floor"},
      {.path = "initial.v_y", .type = T::Number, .unit = "m/s", .defaultText = "0", .lower = closed(-kMaxSpeed),
       .upper = closed(kMaxSpeed), .onlyWith = {is("flight", {"true"})},
       .presenceWhy = "a rolling or sliding coin's height and vertical velocity follow from its attitude and rates",
       .doc = "the centre's vertical velocity (a toss); in flight `v_x` and `v_z` default to 0"},

      {.path = "initial[steady].steady", .type = T::Name, .unit = "", .defaultText = "",
       .names = namesOf(kSteadyKindNames),
       .doc = "instead of rates: the program solves for a steady motion, `straight` (needs `omega_Z`), `circle` "
              "(`theta`, `omega_Z`, optional `branch`) or `spin-in-place` (`theta`)"},
      {.path = "initial[steady].theta", .type = T::Number, .unit = "degrees", .defaultText = "", .required = true,
       .lower = open(-90), .upper = open(90),
       .onlyWith = {is("initial[steady].steady", {R"("circle")", R"("spin-in-place")"})},
       .presenceWhy = "a straight roll is upright", .example = "20",
       .why = "the seed's equations are singular when the coin lies flat",
       .doc = "the steady tilt; required for `circle` and `spin-in-place`, refused for `straight`"},
      {.path = "initial[steady].omega_Z", .type = T::Number, .unit = "rad/s", .defaultText = "", .required = true,
       .lower = closed(-kMaxRate), .upper = closed(kMaxRate),
       .onlyWith = {is("initial[steady].steady", {R"("straight")", R"("circle")"})},
       .presenceWhy = "a coin spinning in place has omega_Z = 0", .example = "10",
       .doc = "the rolling rate; required for `straight` and `circle`, refused for `spin-in-place`"},
      {.path = "initial[steady].branch", .type = T::Name, .unit = "", .defaultText = "\"+\"", .names = {"+", "-"},
       .onlyWith = {is("initial[steady].steady", {R"("circle")"})}, .presenceWhy = "only a circle has two roots",
       .doc = "`circle` only: `+` for the f+ root of the steady circle's equation, `-` for f-"},
      {.path = "initial[steady].phi", .type = T::Number, .unit = "deg", .defaultText = "0",
       .lower = closed(-kMaxAngleDegrees), .upper = closed(kMaxAngleDegrees),
       .why = "an angle is the same modulo 360; reduce it",
       .doc = "the heading"},
      {.path = "initial[steady].psi", .type = T::Number, .unit = "deg", .defaultText = "0",
       .lower = closed(-kMaxAngleDegrees), .upper = closed(kMaxAngleDegrees),
       .why = "an angle is the same modulo 360; reduce it",
       .doc = "the spin angle"},
      {.path = "initial[steady].x", .type = T::Number, .unit = "m", .defaultText = "0", .lower = closed(-kMaxPosition),
       .upper = closed(kMaxPosition),
       .doc = "the centre of mass on the floor"},
      {.path = "initial[steady].z", .type = T::Number, .unit = "m", .defaultText = "0", .lower = closed(-kMaxPosition),
       .upper = closed(kMaxPosition),
       .doc = "the centre of mass on the floor"},

      {.path = "solver.formulation", .type = T::Name, .unit = "", .defaultText = "",
       .names = namesOf(kFormulationNames),
       .doc = "`euler-angles` (the seed's equations) or `quaternion` (no flat-coin singularity); absent, "
              "`euler-angles`, except `quaternion` for a coin with `thickness` and `effects`, whose landing only the "
              "quaternion reaches"},
      {.path = "solver.method", .type = T::Name, .unit = "",
       .defaultText = jsonString(integrate::nameOf(solver.method)),
       .names = {integrate::methodNames().begin(), integrate::methodNames().end()},
       .doc = "`euler`, `rk4` and `gauss4` take fixed steps `dt`; `dopri5` and `dop853` adapt theirs to `rtol`, "
              "`atol`"},
      {.path = "solver.rtol", .type = T::Number, .unit = "", .defaultText = number(solver.rtol),
       .lower = closed(integrate::kMinRtol), .upper = closed(integrate::kMaxRtol),
       .why = "default " + powerOfTen(solver.rtol), .powersOfTen = true,
       .doc = "adaptive methods' relative tolerance per step: tighter is lost in round-off, looser is not worth "
              "reading"},
      {.path = "solver.atol", .type = T::Number, .unit = "", .defaultText = number(solver.atol), .lower = open(0),
       .upper = closed(integrate::kMaxAtol),
       .why = "default " + powerOfTen(solver.atol) + "; 0 cannot weigh a state component that is 0",
       .powersOfTen = true,
       .doc = "adaptive methods' absolute tolerance per step, in the state's units"},
      {.path = "solver.dt", .type = T::Number, .unit = "s", .defaultText = number(solver.dt),
       .lower = closed(integrate::kMinDt), .upper = closed(integrate::kMaxDt),
       .why = "default " + powerOfTen(solver.dt),
       .powersOfTen = true, .doc = "fixed-step methods' step"},
  };

  const std::vector<Key> effects = {
      {.path = "effects[air_drag].type", .type = T::Name, .unit = "", .defaultText = "", .required = true,
       .names = namesOf(kEffectTypeNames),
       .doc = "air drag on the face rolling over the floor (docs/euler_disk.md)"},
      {.path = "effects[air_drag].model", .type = T::Name, .unit = "", .defaultText = nameOf(air.model, kAirFlowNames),
       .names = namesOf(kAirFlowNames),
       .doc = "`moffatt` (lubrication flow filling the gap) or `boundary_layer` (Bildsten's Stokes layer)"},
      {.path = "effects[air_drag].viscosity", .type = T::Number, .unit = "Pa s", .defaultText = number(air.viscosity),
       .lower = open(0), .upper = closed(1e3),
       .doc = "the air's dynamic viscosity (the bound admits glycerine)"},
      {.path = "effects[air_drag].density", .type = T::Number, .unit = "kg/m^3", .defaultText = number(air.density),
       .lower = open(0), .upper = closed(1e5),
       .onlyWith = {is("effects[air_drag].model", {R"("boundary_layer")"})},
       .presenceWhy = "Moffatt's law has no density",
       .doc = "the air's density; `boundary_layer` only"},
      {.path = "effects[rolling_resistance].type", .type = T::Name, .unit = "", .defaultText = "", .required = true,
       .names = namesOf(kEffectTypeNames),
       .doc = "a couple resisting the rim's rolling over the floor"},
      {.path = "effects[rolling_resistance].length", .type = T::Number, .unit = "m",
       .defaultText = number(rolling.length),
       .lower = closed(0),
       .doc = "below `coin.radius`: the energy lost per distance rolled is (length / radius) N"},
      {.path = "effects[rolling_resistance].load_exponent", .type = T::Number, .unit = "",
       .defaultText = number(rolling.loadExponent), .lower = open(0), .upper = closed(2),
       .why = "1: couple proportional to the load",
       .doc = "n: the couple is length x 1 N x (N / 1 N)^n (n < 1: sublinear in the load)"},
      {.path = "effects[rolling_resistance].rate_exponent", .type = T::Number, .unit = "",
       .defaultText = number(rolling.rateExponent), .lower = closed(1), .upper = closed(3),
       .why = "1: a constant couple, power ~ |psi-dot|; 2: power ~ |psi-dot|^2, McDonald and McDonald's measurement",
       .doc = "m: the couple also grows as (|psi-dot| / 1 rad/s)^(m-1), so the power goes as |psi-dot|^m"},
      {.path = "effects[spin_friction].type", .type = T::Name, .unit = "", .defaultText = "", .required = true,
       .names = namesOf(kEffectTypeNames),
       .doc = "a pivoting couple about the floor normal"},
      {.path = "effects[spin_friction].length", .type = T::Number, .unit = "m", .defaultText = number(pivoting.length),
       .lower = closed(0),
       .doc = "below `coin.radius`: the couple is length x N ((2/3) mu r for a contact patch of radius r)"},
  };
  table.insert(table.end(), effects.begin(), effects.end());

  const std::vector<Key> rendering = {
      {.path = "render.width", .type = T::Integer, .unit = "px", .defaultText = number(picture.width),
       .lower = closed(render::kMinImageSide), .upper = closed(render::kMaxImageSide),
       .doc = "even (H.264's yuv420p needs even sizes)"},
      {.path = "render.height", .type = T::Integer, .unit = "px", .defaultText = number(picture.height),
       .lower = closed(render::kMinImageSide), .upper = closed(render::kMaxImageSide),
       .doc = "even (H.264's yuv420p needs even sizes)"},
      {.path = "render.fps", .type = T::Integer, .unit = "1/s", .defaultText = number(render.fps), .lower = closed(1),
       .upper = closed(kMaxFps), .unitInRule = false,
       .doc = "frames per second of video; at most 50 for a `.gif`, whose frame delays are whole hundredths of a "
              "second (docs/outputs.md \"GIF frame timing\")"},
      {.path = "render.antialiasing", .type = T::Name, .unit = "",
       .defaultText = nameOf(picture.antialiasing, kAntialiasingNames), .names = namesOf(kAntialiasingNames),
       .doc = "`auto`: `ssaa` for a still, `ssaa` with one sample for a video from a fixed camera, `msaa` for a "
              "video from a moving one (docs/quality.md \"Anti-aliasing\"); `msaa` (`render.msaa` samples per "
              "pixel, resolved), `ssaa` (drawn at twice the width and height with `render.msaa` samples per pixel "
              "there, each 2x2 block averaged) or `fxaa` (one sample and a fast edge-smoothing pass; `msaa` is then "
              "ignored)"},
      {.path = "render.msaa", .type = T::Integer, .unit = "", .defaultText = number(picture.msaa),
       .doc = fmt::format("samples per pixel (per drawn pixel with `ssaa`; `auto` takes one for a fixed camera's "
                          "video): one of {}, and at most what the OpenGL allows (llvmpipe on Debian 12: 4; more is "
                          "refused, naming the limit)", fmt::join(render::kMsaaSampleCounts, ", "))},
      {.path = "render.time_scale", .type = T::Number, .unit = "", .defaultText = number(render.timeScale),
       .lower = open(0), .doc = "simulated seconds per video second (0.5 = half speed, 2 = twice as fast)"},
      {.path = "render.time_remap", .type = T::Object, .unit = "", .defaultText = "",
       .needsOneOf = {"spin_rate", "precession_rate", "flight", "impact"},
       .presenceWhy = "where the motion is fast, in the air or at each impact",
       .doc = "slow motion: where the motion is fast (one of `spin_rate` and `precession_rate`), in the air "
              "(`flight`), at each impact (`impact`); at least one, and the slowest of them plays"},
      {.path = "render.camera", .type = T::Object, .unit = "", .defaultText = "{}",
       .doc = "where the picture is seen from"},
      {.path = "render.trace", .type = T::Boolean, .unit = "", .defaultText = render.trace ? "true" : "false",
       .doc = "the contact point's trace on the floor, and its marker"},
      {.path = "render.hud", .type = T::Boolean, .unit = "", .defaultText = render.hud ? "true" : "false",
       .doc = "the corner overlay (time, tilt, rates, energy)"},
      {.path = "render.video", .type = T::Object, .unit = "", .defaultText = "{}",
       .doc = "x264's settings for MP4 and MOV"},
      {.path = "render.audio", .type = T::Audio, .unit = "", .defaultText = "false",
       .doc = "`true`, or an object of options: a sound track in the MP4 or MOV whose fundamental is k Omega / 2 pi "
              "(docs/sound.md); PNG sequences ignore it, `.gif` and `.webm` refuse it"},
      {.path = "render.background", .type = T::Name, .unit = "",
       .defaultText = jsonString(kBackgroundNames[picture.transparentBackground ? 1 : 0]),
       .names = namesOf(kBackgroundNames),
       .doc = "`transparent`: no sky and no visible floor, alpha 0 where nothing is drawn; kept by PNGs, `.mov` and "
              "`.webm`, refused with `.mp4` and `.gif`"},
      {.path = "render.provenance", .type = T::Boolean, .unit = "", .defaultText = render.provenance ? "true" : "false",
       .doc = "outputs name `coinroll VERSION` and a digest of the resolved scene (docs/outputs.md); `false` leaves "
              "them out"},
      {.path = "render.theme", .type = T::Name, .unit = "", .defaultText = nameOf(picture.theme, kThemeNames),
       .names = namesOf(kThemeNames),
       .doc = "`classic` (dark floor under a pale sky) or `paper` (for print: white sky, near-white floor, dark text)"},
      {.path = "render.scale_bar", .type = T::ScaleBar, .unit = "m",
       .defaultText = picture.scaleBar.shown ? "true" : "false",
       .lower = open(0), .upper = closed(10),
       .doc = "`true` (the largest 1, 2 or 5 x 10^k m not above the coin's radius) or a length: a labelled bar on the "
              "floor two radii in front of the coin (docs/outputs.md)"},

      {.path = "render.time_remap.spin_rate", .type = T::Number, .unit = "rad/s", .defaultText = "", .lower = open(0),
       .example = "10",
       .doc = "slow down further while |psi-dot| exceeds it, so the spin on screen stays at most this x time_scale"},
      {.path = "render.time_remap.precession_rate", .type = T::Number, .unit = "rad/s", .defaultText = "",
       .lower = open(0), .excludes = {"spin_rate"}, .presenceWhy = "one rate sets the slow-down", .example = "10",
       .doc = "instead of `spin_rate`: the same by Omega = |phi-dot|, the contact point's rate round the floor (what "
              "an Euler's disk speeds up)"},
      {.path = "render.time_remap.growth", .type = T::Number, .unit = "", .defaultText = "0", .lower = closed(0),
       .upper = open(1),
       .onlyWith = {givenOneOf({"render.time_remap.spin_rate", "render.time_remap.precession_rate"})},
       .presenceWhy = "it shapes their slow-down",
       .why = "0 holds the visible rate constant, 0.5 lets it grow as the square root of the real one",
       .doc = "above the limit S the rate on screen is time_scale x S x (rate / S)^growth, at most a quarter turn per "
              "frame"},
      {.path = "render.time_remap.flight", .type = T::Object, .unit = "", .defaultText = "",
       .doc = "slow motion while the coin is in the air (`\"flight\": true`), eased in before each lift-off and out "
              "after each landing"},
      {.path = "render.time_remap.impact", .type = T::Object, .unit = "", .defaultText = "",
       .doc = "slow motion around each impact of the rim (`\"flight\": true`), eased in before it and out after it"},

      {.path = "render.time_remap.flight.slow", .type = T::Number, .unit = "", .defaultText = "", .required = true,
       .lower = open(0), .upper = closed(1), .presenceWhy = "the playback rate in the air, times time_scale",
       .example = "0.25", .doc = "the playback rate in the air, times time_scale (0.25 plays a flight 4x slower)"},
      {.path = "render.time_remap.flight.window", .type = T::Number, .unit = "s",
       .defaultText = number(slowDown.window),
       .lower = closed(0),
       .doc = "simulated time over which the slow-down eases in before a lift-off and out after a landing "
              "(0: at once)"},
      {.path = "render.time_remap.impact.slow", .type = T::Number, .unit = "", .defaultText = "", .required = true,
       .lower = open(0), .upper = closed(1), .presenceWhy = "the playback rate at an impact, times time_scale",
       .example = "0.05",
       .doc = "the playback rate at an impact's instant, times time_scale (0.05 plays it 20x slower)"},
      {.path = "render.time_remap.impact.window", .type = T::Number, .unit = "s",
       .defaultText = number(slowDown.window),
       .lower = open(0),
       .why = "the slow-down eases in and out over it; 0.1 s changes the rate by at most 1.27x a frame at 60 fps",
       .doc = "simulated time before and after each impact over which the slow-down eases in and out; from one "
              "frame to the next the rate changes by at most exp(1.5 (1 - slow) time_scale / (window fps))"},

      {.path = "render.camera.mode", .type = T::Name, .unit = "", .defaultText = nameOf(camera.mode, kCameraModeNames),
       .names = namesOf(kCameraModeNames),
       .doc = "`fixed` (frames the whole motion), `orbit` (circles it once per `orbit_period`), `follow` (tracks the "
              "coin)"},
      {.path = "render.camera.eye", .type = T::Point, .unit = "m", .defaultText = "", .lower = closed(-kMaxPosition),
       .upper = closed(kMaxPosition),
       .doc = "[x, y, z]; absent, framed from the motion; `follow` uses eye - target as its offset"},
      {.path = "render.camera.target", .type = T::Point, .unit = "m", .defaultText = "", .lower = closed(-kMaxPosition),
       .upper = closed(kMaxPosition),
       .doc = "[x, y, z]; absent, framed from the motion"},
      {.path = "render.camera.fov", .type = T::Number, .unit = "degrees", .defaultText = number(camera.fovDegrees),
       .lower = open(1), .upper = open(170), .doc = "the vertical field of view"},
      {.path = "render.camera.orbit_period", .type = T::Number, .unit = "s", .defaultText = number(camera.orbitPeriod),
       .lower = open(0), .doc = "simulated seconds per orbit"},
      {.path = "render.camera.elevation", .type = T::Number, .unit = "degrees",
       .defaultText = number(camera.elevationDegrees), .lower = open(0), .upper = open(90),
       .doc = "the camera's height angle for automatic framing"},

      {.path = "render.video.crf", .type = T::Integer, .unit = "", .defaultText = number(render.video.crf),
       .lower = closed(0), .upper = closed(video::kMaxCrf), .doc = "x264's constant rate factor; lower is better"},
      {.path = "render.video.preset", .type = T::Name, .unit = "", .defaultText = jsonString(render.video.preset),
       .names = namesOf(video::kX264Presets), .doc = "x264's speed preset"},
      {.path = "render.video.threads", .type = T::Integer, .unit = "", .defaultText = number(render.video.threads),
       .lower = closed(1), .upper = closed(video::kMaxX264Threads),
       .doc = "encoder threads, fixed, never \"auto\": x264's bytes depend on it"},

      {.path = "render.audio.pitch", .type = T::Name, .unit = "", .defaultText = nameOf(audio.pitch, kPitchNames),
       .names = namesOf(kPitchNames),
       .doc = "`video` (slow motion lowers the pitch) or `real` (the real motion's pitch)"},
      {.path = "render.audio.timbre", .type = T::Name, .unit = "", .defaultText = nameOf(audio.timbre, kTimbreNames),
       .names = namesOf(kTimbreNames), .doc = "`clicks` (a click per turn of the contact point) or `tone` (a sine)"},
      {.path = "render.audio.frequency_scale", .type = T::Number, .unit = "",
       .defaultText = number(audio.frequencyScale),
       .lower = open(0), .upper = closed(1000), .doc = "k: the fundamental is k Omega / 2 pi; 1 is the physical rate"},
      {.path = "render.audio.volume", .type = T::Number, .unit = "", .defaultText = number(audio.volume),
       .lower = open(0), .upper = closed(1), .doc = "the peak amplitude"},
  };
  table.insert(table.end(), rendering.begin(), rendering.end());
  // clang-format on
  return table;
}

const std::vector<Key>& table() {
  static const std::vector<Key> rows = buildTable();
  return rows;
}

}  // namespace

std::string_view Key::block() const {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? std::string_view() : std::string_view(path).substr(0, dot);
}

std::string_view Key::name() const {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? std::string_view(path) : std::string_view(path).substr(dot + 1);
}

std::span<const Key> keys() { return table(); }

const Key& key(std::string_view path) {
  const auto& rows = table();
  const auto found = std::find_if(rows.begin(), rows.end(), [path](const Key& k) { return k.path == path; });
  if (found == rows.end()) throw std::logic_error(fmt::format("scene schema: no key {}", path));
  return *found;
}

std::span<const std::string_view> keysIn(std::string_view block) {
  static const std::map<std::string, std::vector<std::string_view>, std::less<>> blocks = [] {
    std::map<std::string, std::vector<std::string_view>, std::less<>> byBlock;
    for (const Key& k : table()) byBlock[std::string(k.block())].push_back(k.name());
    return byBlock;
  }();
  const auto found = blocks.find(block);
  if (found == blocks.end()) throw std::logic_error(fmt::format("scene schema: no block {}", block));
  return found->second;
}

std::string rangeViolation(const Key& key, double value) {
  const bool aboveLower = !key.lower || (key.lower->inclusive ? value >= key.lower->value : value > key.lower->value);
  const bool belowUpper = !key.upper || (key.upper->inclusive ? value <= key.upper->value : value < key.upper->value);
  if (aboveLower && belowUpper) return {};
  const auto bound = [&key](double b) { return key.powersOfTen ? powerOfTen(b) : fmt::format("{:g}", b); };
  std::string interval;
  if (key.lower && !key.upper) {
    interval = fmt::format("{} {}", key.lower->inclusive ? ">=" : ">", bound(key.lower->value));
  } else {
    interval = fmt::format("in {}{}, {}{}", key.lower->inclusive ? '[' : '(', bound(key.lower->value),
                           bound(key.upper->value), key.upper->inclusive ? ']' : ')');
    if (key.unitInRule && !key.unit.empty()) interval += " " + key.unit;
  }
  const std::string why = key.why.empty() ? std::string() : fmt::format(" ({})", key.why);
  return fmt::format("must be {}{}, got {}", interval, why, value);
}

std::string quotedAlternatives(std::span<const std::string_view> names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    text += fmt::format("{}\"{}\"", i == 0 ? "" : i + 1 == names.size() ? " or " : ", ", names[i]);
  }
  return text;
}

std::string_view typeName(Type type) {
  switch (type) {
    case Type::Number: return "number";
    case Type::Integer: return "integer";
    case Type::Boolean: return "boolean";
    case Type::Text: return "string";
    case Type::Name: return "name";
    case Type::Point: return "point";
    case Type::Object: return "object";
    case Type::List: return "list";
    case Type::Audio: return "boolean or object";
    case Type::ScaleBar: return "boolean or number";
  }
  return "";
}

namespace {

// "a, b or c".
std::string alternatives(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  }
  return text;
}

}  // namespace

std::string conditionText(const Condition& condition, std::string_view block) {
  std::vector<std::string> names;
  for (const std::string& path : condition.paths) {
    const Key& other = key(path);
    names.emplace_back(other.block() == block ? other.name() : std::string_view(other.path));
  }
  std::string text = alternatives(names);
  if (!condition.values.empty()) text += ": " + alternatives(condition.values);
  return text;
}

std::string presenceText(const Key& key) {
  const auto conditions = [&key](const std::vector<Condition>& list) {
    std::vector<std::string> texts;
    for (const Condition& c : list) texts.push_back(fmt::format("`{}`", conditionText(c, key.block())));
    return fmt::format("{}", fmt::join(texts, " and "));
  };
  std::vector<std::string> rules;
  if (!key.onlyWith.empty()) {
    rules.push_back("only with " + conditions(key.onlyWith) + (key.required ? ", and required there" : ""));
  } else if (key.required) {
    rules.push_back("required");
  }
  if (!key.needs.empty()) rules.push_back("`true` only with " + conditions(key.needs));
  for (const std::string& other : key.excludes) rules.push_back(fmt::format("not with `{}`", other));
  if (!key.needsOneOf.empty()) {
    std::vector<std::string> names;
    for (const std::string& name : key.needsOneOf) names.push_back(fmt::format("`{}`", name));
    rules.push_back("needs one of " + alternatives(names));
  }
  return fmt::format("{}", fmt::join(rules, "; "));
}

namespace {

// "in (0, 10000]", "> 0", "`disk`, `ring` or `custom`": the range column of docs/scene.md.
std::string rangeText(const Key& key) {
  if (!key.names.empty()) {
    std::string text;
    for (std::size_t i = 0; i < key.names.size(); ++i) {
      text += fmt::format("{}`{}`", i == 0 ? "" : i + 1 == key.names.size() ? " or " : ", ", key.names[i]);
    }
    return text;
  }
  const auto bound = [&key](double b) { return key.powersOfTen ? powerOfTen(b) : fmt::format("{:g}", b); };
  if (key.lower && !key.upper) return fmt::format("{} {}", key.lower->inclusive ? "≥" : ">", bound(key.lower->value));
  if (key.lower && key.upper) {
    return fmt::format("{}{}, {}{}", key.lower->inclusive ? '[' : '(', bound(key.lower->value), bound(key.upper->value),
                       key.upper->inclusive ? ']' : ')');
  }
  return {};
}

// A cell's text with the table's separator escaped.
std::string cell(std::string_view text) {
  std::string escaped;
  for (const char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
  return escaped;
}

nlohmann::json conditionsJson(const std::vector<Condition>& conditions) {
  nlohmann::json list = nlohmann::json::array();
  for (const Condition& c : conditions) {
    nlohmann::json entry = {{"paths", c.paths}};
    for (const std::string& value : c.values) entry["values"].push_back(nlohmann::json::parse(value));
    list.push_back(std::move(entry));
  }
  return list;
}

}  // namespace

nlohmann::json toJson() {
  nlohmann::json rows = nlohmann::json::array();
  for (const Key& k : table()) {
    nlohmann::json row = {{"path", k.path}, {"type", typeName(k.type)}, {"doc", k.doc}};
    if (!k.unit.empty()) row["unit"] = k.unit;
    if (!k.defaultText.empty()) row["default"] = nlohmann::json::parse(k.defaultText);
    if (!k.example.empty()) row["example"] = nlohmann::json::parse(k.example);
    if (k.required) row["required"] = true;
    const auto bound = [](const Bound& b) { return nlohmann::json{{"value", b.value}, {"inclusive", b.inclusive}}; };
    if (k.lower) row["minimum"] = bound(*k.lower);
    if (k.upper) row["maximum"] = bound(*k.upper);
    if (!k.names.empty()) row["names"] = k.names;
    if (!k.onlyWith.empty()) row["only_with"] = conditionsJson(k.onlyWith);
    if (!k.needs.empty()) row["needs"] = conditionsJson(k.needs);
    if (!k.excludes.empty()) row["excludes"] = k.excludes;
    if (!k.needsOneOf.empty()) row["needs_one_of"] = k.needsOneOf;
    rows.push_back(std::move(row));
  }
  return {{"schema", "coinroll scene"}, {"keys", std::move(rows)}};
}

std::string toMarkdown() {
  std::string text = "| key | type | unit | default | range | presence | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const Key& k : table()) {
    const std::string fallback = k.defaultText.empty() ? "" : fmt::format("`{}`", k.defaultText);
    text += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", k.path, typeName(k.type), cell(k.unit),
                        cell(fallback), cell(rangeText(k)), cell(presenceText(k)), cell(k.doc));
  }
  return text;
}

std::string toContractMarkdown() {
  std::string text = "| key | type | unit | presence |\n|---|---|---|---|\n";
  for (const Key& k : table()) {
    text += fmt::format("| `{}` | {} | {} | {} |\n", k.path, typeName(k.type), cell(k.unit), cell(presenceText(k)));
  }
  return text;
}

}  // namespace coinroll::scene::schema
