#include "scene/scene_loader.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "integrate/solver_config.h"
#include "scene/json_reader.h"

namespace coinroll::scene {

namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

// The file's names of each enum, in the order of the enum's values.
constexpr std::array<std::string_view, 2> kFormulationNames = {"euler-angles", "quaternion"};
constexpr std::array<std::string_view, 2> kAntialiasingNames = {"msaa", "fxaa"};
constexpr std::array<std::string_view, 3> kShapeNames = {"disk", "ring", "custom"};
constexpr std::array<std::string_view, 3> kSteadyKindNames = {"straight", "circle", "spin-in-place"};
constexpr std::array<std::string_view, 2> kPitchNames = {"video", "real"};
constexpr std::array<std::string_view, 2> kTimbreNames = {"clicks", "tone"};
constexpr std::array<std::string_view, 2> kAirFlowNames = {"moffatt", "boundary_layer"};
constexpr std::array<std::string_view, 2> kOnInvalidNames = {"stop", "warn"};
constexpr std::array<std::string_view, 2> kBackgroundNames = {"opaque", "transparent"};
constexpr std::array<std::string_view, 2> kThemeNames = {"classic", "paper"};  // render::Theme's order

// "a, b or c" (each item through `show`) for the rule of a message.
template <class Items, class Show>
std::string alternatives(const Items& items, Show show) {
  const std::size_t N = std::size(items);
  std::string text;
  for (std::size_t i = 0; i < N; ++i) text += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + show(items[i]);
  return text;
}

// The one mapping from a file's names to an enum: the value named at `key` (`fallback` when
// absent), `names` in the enum's order. A name outside them fails with `rule` when given, else
// with "must be \"a\", \"b\" or \"c\", got \"x\"".
template <class Enum, std::size_t N>
Enum enumValue(const JsonReader& r, std::string_view key, std::span<const std::string_view, N> names, Enum fallback,
               std::string_view rule = {}) {
  const std::optional<std::string> name = r.optionalString(key);
  if (!name) return fallback;
  const auto found = std::find(names.begin(), names.end(), *name);
  if (found == names.end()) {
    r.fail(key, rule.empty() ? fmt::format("must be {}, got \"{}\"",
                                           alternatives(names, [](std::string_view n) { return fmt::format("\"{}\"", n); }), *name)
                             : fmt::format(fmt::runtime(rule), *name));
  }
  return static_cast<Enum>(found - names.begin());
}


// A power of ten as the messages and the README write it: 1e-3, 1e-14, 1.
std::string powerOfTen(double value) {
  const int exponent = static_cast<int>(std::lround(std::log10(value)));
  return exponent == 0 ? fmt::format("{:g}", value) : fmt::format("{:g}e{}", value / std::pow(10.0, exponent), exponent);
}

double positive(const JsonReader& r, std::string_view key, std::optional<double> value) {
  if (value && !(*value > 0)) r.fail(key, fmt::format("must be > 0, got {}", *value));
  return value.value_or(0);
}

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

double inRange(const JsonReader& r, std::string_view key, double value, double lower, double upper, std::string_view unit) {
  if (!(value >= lower && value <= upper)) {
    r.fail(key, fmt::format("must be in [{:g}, {:g}] {}, got {}", lower, upper, unit, value));
  }
  return value;
}

double rate(const JsonReader& r, std::string_view key) { return inRange(r, key, r.number(key, 0), -kMaxRate, kMaxRate, "rad/s"); }

double angleDegrees(const JsonReader& r, std::string_view key) {
  const double degrees = r.number(key, 0);
  if (!(std::abs(degrees) <= kMaxAngleDegrees)) {
    r.fail(key, fmt::format("must be in [{:g}, {:g}] deg (an angle is the same modulo 360; reduce it), got {}",
                            -kMaxAngleDegrees, kMaxAngleDegrees, degrees));
  }
  return degrees * kRadiansPerDegree;
}

double position(const JsonReader& r, std::string_view key) {
  return inRange(r, key, r.number(key, 0), -kMaxPosition, kMaxPosition, "m");
}

double tiltDegrees(const JsonReader& r, std::string_view key, double fallback) {
  const double degrees = r.number(key, fallback);
  if (!(std::abs(degrees) < 90)) {
    r.fail(key, fmt::format("must be in (-90, 90) degrees (the seed's equations are singular when the coin lies flat), "
                            "got {}", degrees));
  }
  return degrees * kRadiansPerDegree;
}

// The coin block: its physics into the returned CoinSpec, its shape as drawn into `drawn`.
CoinSpec parseCoin(const JsonReader& top, render::CoinShape& drawn) {
  const nlohmann::json* node = top.child("coin");
  if (node == nullptr) top.fail("coin", "required (an object with shape, radius, mass)");
  const JsonReader r(*node, "coin", "", {"shape", "radius", "mass", "inner_radius", "thickness", "edge_radius", "I_X", "I_Z"});
  CoinSpec coin;
  coin.shape = enumValue(r, "shape", std::span(kShapeNames), coin.shape);
  const std::string_view shape = kShapeNames[static_cast<std::size_t>(coin.shape)];

  coin.radius = inRange(r, "radius", r.requiredNumber("radius"), kMinLength, kMaxLength, "m");
  coin.mass = inRange(r, "mass", r.requiredNumber("mass"), kMinMass, kMaxMass, "kg");
  const double thickness = inRange(r, "thickness", r.number("thickness", 0.06 * coin.radius), kMinLength * 0.06, kMaxLength, "m");

  if (r.has("inner_radius") && coin.shape != Shape::Ring) r.fail("inner_radius", "only allowed with shape \"ring\"");
  coin.innerRadius = r.number("inner_radius", coin.radius);
  if (coin.shape == Shape::Ring && !(coin.innerRadius >= 0 && coin.innerRadius <= coin.radius)) {
    r.fail("inner_radius", fmt::format("must be in [0, radius = {}] m, got {}", coin.radius, coin.innerRadius));
  }
  if (r.has("thickness")) coin.thickness = thickness;
  if (r.has("edge_radius") && !coin.thickness) {
    r.fail("edge_radius", "only allowed with coin.thickness (a thin coin has no rim to round)");
  }
  if (coin.thickness) {
    const double hole = coin.shape == Shape::Ring ? coin.innerRadius : 0.0;
    const double largest = std::min(0.5 * thickness, coin.radius - hole);
    coin.edgeRadius = r.number("edge_radius", largest);
    if (!(coin.edgeRadius >= 0 && coin.edgeRadius <= largest)) {
      // Name the bound that holds; {:.15g}: 0.0375 - 0.037 would print as 0.0005000000000000004.
      const std::string widthBound =
          coin.shape == Shape::Ring        ? fmt::format(" and radius - inner_radius = {:.15g} m, the ring's width", coin.radius - hole)
          : coin.radius < 0.5 * thickness ? fmt::format(" and radius = {:.15g} m", coin.radius)
                                          : std::string();
      r.fail("edge_radius", fmt::format("must be in [0, {:.15g}] m (at most thickness / 2 = {:.15g} m{}), got {}", largest,
                                        0.5 * thickness, widthBound, coin.edgeRadius));
    }
    drawn.edgeRadius = static_cast<float>(coin.edgeRadius);
  }
  drawn.radius = static_cast<float>(coin.radius);
  drawn.thickness = static_cast<float>(thickness);
  if (coin.shape == Shape::Ring) {
    // A thin hoop (b = a) is drawn as a band as wide as it is thick, so it stays visible.
    const double band = std::max(thickness, 0.04 * coin.radius);
    drawn.innerRadius = static_cast<float>(std::min(coin.innerRadius, coin.radius - band));
  }

  if (coin.shape != Shape::Custom) {
    for (std::string_view key : {"I_X", "I_Z"}) {
      if (r.has(key)) r.fail(key, fmt::format("only allowed with shape \"custom\" ({} fixes the inertia)", shape));
    }
    return coin;
  }
  coin.I_X = r.optionalNumber("I_X");
  coin.I_Z = r.optionalNumber("I_Z");
  if (!coin.I_X) r.fail("I_X", "required for shape \"custom\" (moment about a diameter, kg m^2)");
  if (!coin.I_Z) r.fail("I_Z", "required for shape \"custom\" (moment about the symmetry axis, kg m^2)");
  // Bounded by what the mass and radius ranges allow for any body, with room for long bodies.
  const double maxInertia = kMaxMass * kMaxLength * kMaxLength, minInertia = kMinMass * kMinLength * kMinLength;
  inRange(r, "I_X", *coin.I_X, minInertia, maxInertia, "kg m^2");
  inRange(r, "I_Z", *coin.I_Z, minInertia, maxInertia, "kg m^2");
  // Perpendicular-axis bound: I_Z = sum m (X^2 + Y^2) <= 2 I_X = sum m (X^2 + Y^2 + 2 Z^2);
  // equality is the flat lamina. The relative slack only forgives round-off in the input.
  if (*coin.I_Z > 2 * *coin.I_X * (1 + 1e-12)) {
    r.fail("I_Z", fmt::format("must be <= 2 I_X = {} (perpendicular-axis theorem for any axisymmetric body), got {}",
                              2 * *coin.I_X, *coin.I_Z));
  }
  return coin;
}

InitialSpec parseInitial(const JsonReader& top) {
  const nlohmann::json* node = top.child("initial");
  if (node == nullptr) {
    top.fail("initial", "required: give angles and rates, or a steady state like {\"steady\": \"circle\", \"theta\": 20, "
                        "\"omega_Z\": 10}");
  }
  if (node->is_object() && node->contains("steady")) {
    // Before the keys: with a steady kind that is not a name, the message is about the kind, not
    // about the explicit start's rates beside it.
    if (const nlohmann::json& kind = node->at("steady"); !kind.is_string()) {
      JsonReader(nlohmann::json::object(), "initial", "", {}).fail(
          "steady", "must be \"straight\", \"circle\" or \"spin-in-place\", got " + describeJson(kind), SceneError::Kind::WrongType);
    }
    const JsonReader r(*node, "initial", "", {"steady", "theta", "omega_Z", "branch", "phi", "psi", "x", "z"});
    SteadyInitial s;
    s.kind = enumValue(r, "steady", std::span(kSteadyKindNames), s.kind);
    const std::string_view kind = kSteadyKindNames[static_cast<std::size_t>(s.kind)];
    const bool needsTheta = s.kind != SteadyKind::Straight, needsSpin = s.kind != SteadyKind::SpinInPlace;
    if (needsTheta && !r.has("theta")) r.fail("theta", fmt::format("required for steady \"{}\" (degrees)", kind));
    if (!needsTheta && r.has("theta")) r.fail("theta", "not allowed for steady \"straight\" (it rolls upright)");
    if (needsSpin && !r.has("omega_Z")) r.fail("omega_Z", fmt::format("required for steady \"{}\" (rad/s)", kind));
    if (!needsSpin && r.has("omega_Z")) r.fail("omega_Z", "not allowed for steady \"spin-in-place\" (omega_Z = 0 there)");
    if (r.has("branch") && s.kind != SteadyKind::Circle) r.fail("branch", "only allowed for steady \"circle\"");
    s.theta = tiltDegrees(r, "theta", 0);
    s.omega_Z = rate(r, "omega_Z");
    const std::string branch = r.optionalString("branch").value_or("+");
    if (branch != "+" && branch != "-") r.fail("branch", fmt::format("must be \"+\" or \"-\", got \"{}\"", branch));
    s.branch = branch == "+" ? 1 : -1;
    s.phi = angleDegrees(r, "phi");
    s.psi = angleDegrees(r, "psi");
    s.x = position(r, "x");
    s.z = position(r, "z");
    return s;
  }
  const JsonReader r(*node, "initial", "", {"theta", "phi", "psi", "omega_X", "omega_Y", "omega_Z", "x", "z", "v_x", "v_z"});
  ExplicitInitial e;
  e.theta = tiltDegrees(r, "theta", 0);
  e.phi = angleDegrees(r, "phi");
  e.psi = angleDegrees(r, "psi");
  e.omega_X = rate(r, "omega_X");
  e.omega_Y = rate(r, "omega_Y");
  e.omega_Z = rate(r, "omega_Z");
  e.x = position(r, "x");
  e.z = position(r, "z");
  if (r.has("v_x") || r.has("v_z")) {
    const auto speed = [&r](std::string_view key) { return inRange(r, key, r.number(key, 0), -kMaxSpeed, kMaxSpeed, "m/s"); };
    e.velocity = std::array<double, 2>{speed("v_x"), speed("v_z")};
  }
  return e;
}

SolverSpec parseSolver(const JsonReader& top) {
  SolverSpec solver;
  const nlohmann::json* node = top.child("solver");
  if (node == nullptr) return solver;
  const JsonReader r(*node, "solver", "", {"formulation", "method", "rtol", "atol", "dt"});
  if (r.has("formulation")) {
    solver.formulation = enumValue(r, "formulation", std::span(kFormulationNames), Formulation{},
                                   fmt::format("unknown formulation \"{{}}\"; available: {}", fmt::join(kFormulationNames, ", ")));
  }
  if (const std::optional<std::string> method = r.optionalString("method")) {
    const std::optional<integrate::Method> known = integrate::methodFromName(*method);
    if (!known) {
      r.fail("method", fmt::format("unknown method \"{}\"; available: {}", *method, fmt::join(integrate::methodNames(), ", ")));
    }
    solver.method = *known;
  }
  // The ranges' reasons are given with them in integrate/solver_config.h.
  const SolverSpec defaults;
  solver.rtol = r.number("rtol", solver.rtol);
  if (!(solver.rtol >= integrate::kMinRtol && solver.rtol <= integrate::kMaxRtol)) {
    r.fail("rtol", fmt::format("must be in [{}, {}] (default {}), got {}", powerOfTen(integrate::kMinRtol),
                               powerOfTen(integrate::kMaxRtol), powerOfTen(defaults.rtol), solver.rtol));
  }
  solver.atol = r.number("atol", solver.atol);
  if (!(solver.atol > 0 && solver.atol <= integrate::kMaxAtol)) {
    r.fail("atol", fmt::format("must be in (0, {}] (default {}; 0 cannot weigh a state component that is 0), got {}",
                               powerOfTen(integrate::kMaxAtol), powerOfTen(defaults.atol), solver.atol));
  }
  solver.dt = r.number("dt", solver.dt);
  if (!(solver.dt >= integrate::kMinDt && solver.dt <= integrate::kMaxDt)) {
    r.fail("dt", fmt::format("must be in [{}, {}] s (default {}), got {}", powerOfTen(integrate::kMinDt),
                             powerOfTen(integrate::kMaxDt), powerOfTen(defaults.dt), solver.dt));
  }
  return solver;
}

std::array<double, 3> parsePoint(const JsonReader& r, std::string_view key) {
  const nlohmann::json* node = r.child(key);
  if (!node->is_array() || node->size() != 3 || !std::all_of(node->begin(), node->end(), [](const auto& v) {
        return v.is_number() && std::isfinite(v.template get<double>());
      })) {
    r.fail(key, "must be an array of three finite numbers [x, y, z] in m, got " + describeJson(*node),
           node->is_array() ? SceneError::Kind::BadValue : SceneError::Kind::WrongType);
  }
  const std::array<double, 3> point{(*node)[0].get<double>(), (*node)[1].get<double>(), (*node)[2].get<double>()};
  // The coin is centimetres across: a camera farther than the positions allowed sees nothing, and
  // squares of its distance would overflow.
  if (std::any_of(point.begin(), point.end(), [](double v) { return std::abs(v) > kMaxPosition; })) {
    r.fail(key, fmt::format("coordinates must be within [{:g}, {:g}] m, got [{}, {}, {}]", -kMaxPosition, kMaxPosition,
                            point[0], point[1], point[2]));
  }
  return point;
}

CameraSpec parseCamera(const JsonReader& render) {
  CameraSpec camera;
  const nlohmann::json* node = render.child("camera");
  if (node == nullptr) return camera;
  const JsonReader r(*node, "render.camera", "", {"mode", "eye", "target", "fov", "orbit_period", "elevation"});
  camera.mode = enumValue(r, "mode", std::span(kCameraModeNames), camera.mode);
  if (r.has("eye")) camera.eye = parsePoint(r, "eye");
  if (r.has("target")) camera.target = parsePoint(r, "target");
  if (camera.eye && camera.target) {
    // The view direction must exist and not be vertical: the camera's "up" is the floor normal y.
    const std::array<double, 3>& e = *camera.eye;
    const std::array<double, 3>& t = *camera.target;
    const double dx = t[0] - e[0], dy = t[1] - e[1], dz = t[2] - e[2];
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz), horizontal = std::hypot(dx, dz);
    if (!(length > 1e-6)) r.fail("target", "must differ from eye (the camera needs a direction to look in)");
    if (!(horizontal > 1e-3 * length)) {
      r.fail("target", "must not lie straight above or below eye (the picture's up is the floor normal; tilt the view "
                       "slightly)");
    }
  }
  camera.fovDegrees = r.number("fov", camera.fovDegrees);
  if (!(camera.fovDegrees > 1 && camera.fovDegrees < 170)) r.fail("fov", fmt::format("must be in (1, 170) degrees, got {}", camera.fovDegrees));
  camera.orbitPeriod = r.number("orbit_period", camera.orbitPeriod);
  positive(r, "orbit_period", camera.orbitPeriod);
  camera.elevationDegrees = r.number("elevation", camera.elevationDegrees);
  if (!(camera.elevationDegrees > 0 && camera.elevationDegrees < 90)) {
    r.fail("elevation", fmt::format("must be in (0, 90) degrees, got {}", camera.elevationDegrees));
  }
  return camera;
}

std::optional<AudioSpec> parseAudio(const JsonReader& render) {
  const nlohmann::json* node = render.child("audio");
  if (node == nullptr || (node->is_boolean() && !node->get<bool>())) return std::nullopt;
  AudioSpec audio;
  if (node->is_boolean()) return audio;
  if (!node->is_object()) render.fail("audio", "must be true, false or an object of options, got " + describeJson(*node));
  const JsonReader a(*node, "render.audio", "", {"pitch", "timbre", "frequency_scale", "volume"});
  audio.pitch = enumValue(a, "pitch", std::span(kPitchNames), audio.pitch,
                          "must be \"video\" (follows slow motion) or \"real\", got \"{}\"");
  audio.timbre = enumValue(a, "timbre", std::span(kTimbreNames), audio.timbre);
  audio.frequencyScale = a.number("frequency_scale", audio.frequencyScale);
  if (!(audio.frequencyScale > 0 && audio.frequencyScale <= 1000)) {
    a.fail("frequency_scale", fmt::format("must be in (0, 1000], got {}", audio.frequencyScale));
  }
  audio.volume = a.number("volume", audio.volume);
  if (!(audio.volume > 0 && audio.volume <= 1)) a.fail("volume", fmt::format("must be in (0, 1], got {}", audio.volume));
  return audio;
}

RenderSpec parseRender(const JsonReader& top) {
  RenderSpec render;
  const nlohmann::json* node = top.child("render");
  if (node == nullptr) return render;
  const JsonReader r(*node, "render", "", {"width", "height", "fps", "antialiasing", "msaa", "time_scale", "time_remap", "camera", "trace", "hud", "video", "audio", "background", "provenance", "theme", "scale_bar"});
  render::RenderSettings& picture = render.picture;
  for (auto [key, field] : {std::pair{"width", &picture.width}, std::pair{"height", &picture.height}}) {
    *field = r.integer(key, *field);
    if (*field < render::kMinImageSide || *field > render::kMaxImageSide || *field % 2 != 0) {
      r.fail(key, fmt::format("must be an even number of pixels in [{}, {}] (H.264 yuv420p needs even sizes), got {}",
                              render::kMinImageSide, render::kMaxImageSide, *field));
    }
  }
  render.fps = r.integer("fps", render.fps);
  if (render.fps < 1 || render.fps > kMaxFps) r.fail("fps", fmt::format("must be in [1, {}], got {}", kMaxFps, render.fps));
  picture.antialiasing = enumValue(r, "antialiasing", std::span(kAntialiasingNames), picture.antialiasing);
  picture.msaa = r.integer("msaa", picture.msaa);
  if (!render::isMsaaSampleCount(picture.msaa)) {
    r.fail("msaa", fmt::format("must be {} samples, got {}",
                               alternatives(render::kMsaaSampleCounts, [](int n) { return std::to_string(n); }), picture.msaa));
  }
  render.timeScale = r.number("time_scale", render.timeScale);
  positive(r, "time_scale", render.timeScale);
  if (const nlohmann::json* remap = r.child("time_remap")) {
    const JsonReader m(*remap, "render.time_remap", "", {"spin_rate", "precession_rate", "growth"});
    if (m.has("spin_rate") == m.has("precession_rate")) {
      r.fail("time_remap", "give exactly one of spin_rate (slow down by psi-dot) or precession_rate (by phi-dot, the "
                           "contact point's rate round the floor), in rad/s");
    }
    const std::string_view key = m.has("spin_rate") ? "spin_rate" : "precession_rate";
    const double limit = m.number(key, 0);
    if (!(limit > 0)) m.fail(key, fmt::format("must be a rate > 0 rad/s, got {}", limit));
    const double growth = m.number("growth", 0);
    if (!(growth >= 0 && growth < 1)) {
      m.fail("growth", fmt::format("must be in [0, 1) (0 holds the visible rate constant, 0.5 lets it grow as the "
                                   "square root of the real one), got {}", growth));
    }
    render.timeRemap = TimeRemap{.rate = key == "spin_rate" ? TimeRemap::Rate::Spin : TimeRemap::Rate::Precession,
                                 .limit = limit,
                                 .growth = growth};
  }
  render.camera = parseCamera(r);
  render.trace = r.boolean("trace", render.trace);
  render.hud = r.boolean("hud", render.hud);
  if (const nlohmann::json* video = r.child("video")) {
    const JsonReader v(*video, "render.video", "", {"crf", "preset", "threads"});
    video::X264Options& x264 = render.video;
    x264.crf = v.integer("crf", x264.crf);
    if (x264.crf < 0 || x264.crf > video::kMaxCrf) v.fail("crf", fmt::format("must be in [0, {}], got {}", video::kMaxCrf, x264.crf));
    x264.preset = v.optionalString("preset").value_or(x264.preset);
    if (std::find(video::kX264Presets.begin(), video::kX264Presets.end(), x264.preset) == video::kX264Presets.end()) {
      v.fail("preset", fmt::format("must be one of {}, got \"{}\"", fmt::join(video::kX264Presets, ", "), x264.preset));
    }
    x264.threads = v.integer("threads", x264.threads);
    if (x264.threads < 1 || x264.threads > video::kMaxX264Threads) {
      v.fail("threads", fmt::format("must be in [1, {}], got {}", video::kMaxX264Threads, x264.threads));
    }
  }
  render.audio = parseAudio(r);
  picture.transparentBackground = enumValue(r, "background", std::span(kBackgroundNames), 0,
                                            "expected \"opaque\" or \"transparent\", got \"{}\"") == 1;
  render.provenance = r.boolean("provenance", render.provenance);
  picture.theme = enumValue(r, "theme", std::span(kThemeNames), picture.theme);
  constexpr std::string_view kScaleBarRule = "must be true, false or a length in (0, 10] m, got ";
  if (const nlohmann::json* bar = r.child("scale_bar"); bar != nullptr && bar->is_number()) {
    picture.scaleBar = {.shown = true, .metres = static_cast<float>(r.number("scale_bar", 0))};
    if (!(picture.scaleBar.metres > 0 && picture.scaleBar.metres <= 10)) r.fail("scale_bar", std::string(kScaleBarRule) + describeJson(*bar));
  } else if (bar != nullptr && !bar->is_boolean()) {
    r.fail("scale_bar", std::string(kScaleBarRule) + describeJson(*bar), SceneError::Kind::WrongType);
  } else {
    picture.scaleBar.shown = r.boolean("scale_bar", picture.scaleBar.shown);
  }
  return render;
}

double nonNegative(const JsonReader& r, std::string_view key, double value) {
  if (!(value >= 0)) r.fail(key, fmt::format("must be >= 0, got {}", value));
  return value;
}

// One entry of "effects" (docs/euler_disk.md §2); defaults are the laws' own member initializers.
physics::Effect parseEffect(const nlohmann::json& node, const std::string& path) {
  if (!node.is_object() || !node.contains("type") || !node["type"].is_string()) {
    throw SceneError(fmt::format("{}: must be an object with a \"type\": \"air_drag\", \"rolling_resistance\" or "
                                 "\"spin_friction\", got {}", path, describeJson(node)),
                     node.is_object() ? SceneError::Kind::BadValue : SceneError::Kind::WrongType);
  }
  const std::string type = node["type"].get<std::string>();
  if (type == "air_drag") {
    const JsonReader r(node, path, "", {"type", "model", "viscosity", "density"});
    physics::AirDrag law;
    law.model = enumValue(r, "model", std::span(kAirFlowNames), law.model);
    law.viscosity = r.number("viscosity", law.viscosity);
    positive(r, "viscosity", law.viscosity);
    // Air is 1.8e-5 Pa s; the bound admits glycerine and stops overflow in the couple.
    inRange(r, "viscosity", law.viscosity, 0, 1e3, "Pa s");
    if (law.model == physics::AirFlow::Moffatt && r.has("density")) {
      r.fail("density", "only used by model \"boundary_layer\" (Moffatt's law has no density); remove it or set "
                        "\"model\": \"boundary_layer\"");
    }
    law.density = r.number("density", law.density);
    positive(r, "density", law.density);
    inRange(r, "density", law.density, 0, 1e5, "kg/m^3");
    return law;
  }
  if (type == "rolling_resistance") {
    const JsonReader r(node, path, "", {"type", "length", "load_exponent", "rate_exponent"});
    physics::RollingResistance law;
    law.length = nonNegative(r, "length", r.number("length", law.length));
    law.loadExponent = r.number("load_exponent", law.loadExponent);
    if (!(law.loadExponent > 0 && law.loadExponent <= 2)) {
      r.fail("load_exponent", fmt::format("must be in (0, 2] (1: couple proportional to the load), got {}", law.loadExponent));
    }
    law.rateExponent = r.number("rate_exponent", law.rateExponent);
    if (!(law.rateExponent >= 1 && law.rateExponent <= 3)) {
      r.fail("rate_exponent", fmt::format("must be in [1, 3] (1: a constant couple, power ~ |psi-dot|; 2: power ~ "
                                          "|psi-dot|^2, McDonald and McDonald's measurement), got {}", law.rateExponent));
    }
    return law;
  }
  if (type == "spin_friction") {
    const JsonReader r(node, path, "", {"type", "length"});
    physics::SpinFriction law;
    law.length = nonNegative(r, "length", r.number("length", law.length));
    return law;
  }
  throw SceneError(fmt::format("{}.type: must be \"air_drag\", \"rolling_resistance\" or \"spin_friction\", got \"{}\"",
                               path, type));
}

// Rolling resistance and pivoting friction are couples N * length whose lever arm lies inside the
// contact patch, so a length at or past the coin's radius has no meaning (and a huge one only
// stalls the integrator).
void refuseLeverArmsPastTheRim(const std::vector<physics::Effect>& effects, double radius) {
  for (std::size_t i = 0; i < effects.size(); ++i) {
    double length = 0;
    if (const auto* rolling = std::get_if<physics::RollingResistance>(&effects[i])) length = rolling->length;
    else if (const auto* pivoting = std::get_if<physics::SpinFriction>(&effects[i])) length = pivoting->length;
    if (!(length < radius)) {
      throw SceneError(fmt::format("effects[{}].length: must be below coin.radius = {} m (the couple's lever arm lies "
                                   "inside the contact patch), got {}", i, radius, length));
    }
  }
}

std::vector<physics::Effect> parseEffects(const JsonReader& top) {
  const nlohmann::json* node = top.child("effects");
  if (node == nullptr) return {};
  if (!node->is_array()) top.fail("effects", "must be a list of effects, e.g. [{\"type\": \"air_drag\"}], got " + describeJson(*node),
                                  SceneError::Kind::WrongType);
  std::vector<physics::Effect> effects;
  for (std::size_t i = 0; i < node->size(); ++i) {
    const std::string path = fmt::format("effects[{}]", i);
    physics::Effect effect = parseEffect((*node)[i], path);
    for (const physics::Effect& earlier : effects) {
      if (earlier.index() == effect.index()) {
        throw SceneError(fmt::format("{}: a second \"{}\"; each law may appear once (merge their parameters)", path,
                                     physics::typeName(effect)));
      }
    }
    effects.push_back(effect);
  }
  return effects;
}

// 1-based line and column of a byte offset in `text`.
std::pair<std::size_t, std::size_t> lineAndColumn(std::string_view text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < std::min(byte, text.size()); ++i) {
    if (text[i] == '\n') ++line, column = 1;
    else ++column;
  }
  return {line, column};
}

// nlohmann's parse error without its own position prefix (we give line and column) and with the
// bytes it quotes from the input made printable: the input may be anything, even not UTF-8.
std::string parseErrorReason(const nlohmann::json::parse_error& error) {
  std::string_view what = error.what();
  if (const auto column = what.find(", column "); column != std::string_view::npos) {
    if (const auto colon = what.find(": ", column); colon != std::string_view::npos) what.remove_prefix(colon + 2);
  }
  std::string reason;
  for (const char c : what) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f) reason += fmt::format("\\x{:02x}", byte);
    else reason += c;
  }
  return reason;
}

// A key given twice in one object: nlohmann keeps the last value silently, so a scene that says
// theta twice would run with whichever came last. Thrown from the parser's callback.
struct DuplicateKey {
  std::string path;  // "initial.theta", "effects.0.length"
};

// The parser's callback, refusing duplicate keys. It follows the nesting: each open object keeps
// the keys seen so far, each open array its element count, so a duplicate is named by its path.
class DuplicateKeyGuard {
 public:
  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        frames_.push_back(
            {.name = nameOfNextValue(), .isArray = event == Event::array_start, .elements = 0, .keys = {}, .pendingKey = {}});
        break;
      case Event::object_end:
      case Event::array_end:
        frames_.pop_back();
        break;
      case Event::key: {
        std::string key = parsed.get<std::string>();
        if (!frames_.back().keys.insert(key).second) throw DuplicateKey{joinedPath(key)};
        frames_.back().pendingKey = std::move(key);
        break;
      }
      case Event::value:
        nameOfNextValue();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    std::string name;  // the key or index this object or array has in its parent
    bool isArray = false;
    long elements = 0;
    std::set<std::string> keys;
    std::string pendingKey;
  };

  // The name of the value that starts now in the innermost open object or array.
  std::string nameOfNextValue() {
    if (frames_.empty()) return {};
    Frame& parent = frames_.back();
    return parent.isArray ? std::to_string(parent.elements++) : parent.pendingKey;
  }

  std::string joinedPath(const std::string& key) const {
    std::string path;
    for (std::size_t i = 1; i < frames_.size(); ++i) path += printableKey(frames_[i].name) + ".";
    return path + printableKey(key);
  }

  std::vector<Frame> frames_;
};

}  // namespace

SceneConfig parseScene(const nlohmann::json& document, std::string_view sourceName) {
  try {
    const JsonReader top(document, "", sourceName,
                         {"name", "coin", "gravity", "friction", "friction_static", "sliding", "initial", "duration", "solver",
                          "effects", "on_invalid", "render"});
    SceneConfig scene;
    scene.name = top.optionalString("name").value_or(scene.name);
    render::CoinShape drawnCoin;
    scene.coin = parseCoin(top, drawnCoin);
    scene.gravity = top.number("gravity", scene.gravity);
    if (!(scene.gravity > 0 && scene.gravity <= kMaxGravity)) {
      top.fail("gravity", fmt::format("must be in (0, {:g}] m/s^2, got {}", kMaxGravity, scene.gravity));
    }
    scene.friction = top.optionalNumber("friction");
    if (scene.friction && !(*scene.friction >= 0)) top.fail("friction", fmt::format("must be >= 0, got {}", *scene.friction));
    scene.frictionStatic = top.optionalNumber("friction_static");
    if (scene.frictionStatic && !scene.friction) {
      top.fail("friction_static", "needs friction (the kinetic coefficient, which it must be at least)");
    }
    if (scene.frictionStatic && !(*scene.frictionStatic >= *scene.friction && std::isfinite(*scene.frictionStatic))) {
      top.fail("friction_static", fmt::format("must be >= friction = {} (static friction is at least kinetic), got {}",
                                              *scene.friction, *scene.frictionStatic));
    }
    scene.sliding = top.boolean("sliding", false);
    if (scene.sliding && !scene.friction) {
      top.fail("sliding", "needs friction (the coefficient of Coulomb friction while the coin slides), e.g. \"friction\": 0.3");
    }
    scene.initial = parseInitial(top);
    if (const auto* e = std::get_if<ExplicitInitial>(&scene.initial); e && e->velocity && !scene.sliding) {
      top.fail("initial.v_x", "only with \"sliding\": true (a rolling coin's velocity follows from its rates)");
    }
    scene.duration = top.requiredNumber("duration");
    positive(top, "duration", scene.duration);
    scene.solver = parseSolver(top);
    // A fixed-step run's step count is known now; the integrator would only find it after hours.
    if (!integrate::isAdaptive(scene.solver.method)) {
      const double steps = scene.duration / scene.solver.dt;
      if (const long maxSteps = integrate::SolverConfig{}.maxSteps; steps > static_cast<double>(maxSteps)) {
        throw SceneError(fmt::format("solver.dt: duration / dt = {:.3g} steps of {}, more than the {} a run may take; "
                                     "raise solver.dt, shorten the duration or use an adaptive method (dop853)",
                                     steps, integrate::nameOf(scene.solver.method), maxSteps));
      }
    }
    scene.effects = parseEffects(top);
    refuseLeverArmsPastTheRim(scene.effects, scene.coin.radius);
    scene.onInvalid = enumValue(top, "on_invalid", std::span(kOnInvalidNames), scene.onInvalid);
    scene.render = parseRender(top);
    scene.render.picture.coin = drawnCoin;
    return scene;
  } catch (const SceneError& e) {
    // Readers of nested objects do not know the source name; add it once here.
    const std::string message = e.what();
    if (message.rfind(std::string(sourceName) + ":", 0) == 0) throw;
    throw SceneError(fmt::format("{}: {}", sourceName, message.substr(message.find_first_not_of(": "))), e.kind());
  }
}

nlohmann::json readSceneDocument(const std::filesystem::path& file) {
  if (file.empty()) {
    throw SceneError("the scene file name is empty; give a scene file (e.g. examples/steady_circle.json), or none for "
                     "the built-in scene");
  }
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) {
    throw SceneError(fmt::format("{}: is a directory; give a scene file (JSON)", file.string()));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(fmt::format("{}: cannot open the scene file: {}", file.string(), std::strerror(errno)));
  // Scenes are a few hundred bytes. The read stops past this, so a huge file given by mistake, or
  // a device that never ends (/dev/zero), is refused instead of filling memory; pipes still work.
  constexpr std::size_t kMaxSceneBytes = 16 << 20;
  std::string text(kMaxSceneBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxSceneBytes) {
    throw SceneError(fmt::format("{}: more than {} bytes; a scene file is a small JSON document", file.string(), kMaxSceneBytes));
  }
  return parseSceneText(text, file.string());
}

nlohmann::json parseSceneText(std::string_view text, std::string_view sourceName) {
  // nlohmann's lexer takes a NUL byte for the end of the input, so whatever follows one would go
  // unread: a damaged file, or a binary one, would pass as the scene before it.
  if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
    const auto [line, column] = lineAndColumn(text, nul);
    throw SceneError(fmt::format("{}: invalid JSON at line {}, column {}: a NUL byte; a scene file is JSON text "
                                 "(a damaged or binary file?)", sourceName, line, column));
  }
  try {
    return nlohmann::json::parse(text, DuplicateKeyGuard());
  } catch (const DuplicateKey& duplicate) {
    throw SceneError(fmt::format("{}: {}: given twice; give each key once (which value was meant?)", sourceName,
                                 duplicate.path));
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports the byte just past the offending token; its own text says what was expected.
    const auto [line, column] = lineAndColumn(text, e.byte == 0 ? 0 : e.byte - 1);
    throw SceneError(fmt::format("{}: invalid JSON at line {}, column {}: {}", sourceName, line, column, parseErrorReason(e)));
  } catch (const nlohmann::json::exception& e) {
    // E.g. a number beyond double range ("1e400"): not finite, so never a valid value.
    std::string reason = e.what();
    if (const auto bracket = reason.find("] "); bracket != std::string::npos) reason = reason.substr(bracket + 2);
    throw SceneError(fmt::format("{}: invalid JSON: {} (numbers must be finite doubles)", sourceName, reason));
  }
}

SceneConfig loadScene(const std::filesystem::path& file, std::span<const std::string> overrides) {
  nlohmann::json document = readSceneDocument(file);
  for (const std::string& assignment : overrides) applyOverride(document, assignment);
  return parseScene(document, file.string());
}

void applyOverride(nlohmann::json& document, std::string_view assignment) {
  const auto equals = assignment.find('=');
  const std::string_view path = assignment.substr(0, equals);
  if (equals == std::string_view::npos || path.empty() || path.front() == '.' || path.back() == '.' ||
      path.find("..") != std::string_view::npos) {
    throw SceneError(fmt::format("--set {}: expected KEY.PATH=VALUE, e.g. --set initial.theta=12", assignment),
                     SceneError::Kind::UnknownKey);
  }
  const std::string text(assignment.substr(equals + 1));
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;
  try {
    // A scene is JSON, so UTF-8: refused here, the bytes would fail later wherever the document
    // is written out again (a sweep's identity) with a library's message.
    (void)value.dump();
  } catch (const nlohmann::json::type_error&) {
    throw SceneError(fmt::format("--set {}: the value is not UTF-8 text; scene values are UTF-8, as in a JSON file",
                                 printableKey(path)));
  }

  // Objects are walked by key, lists (effects) by index: effects.0.length is the first effect's
  // length. A missing key is created as an object; a list is never created or lengthened, since
  // a half-given entry (an effect without its type) would only fail later with a vaguer message.
  nlohmann::json* node = &document;
  std::string_view rest = path;
  std::string walked;  // the path so far, for messages
  while (true) {
    const auto dot = rest.find('.');
    const std::string key(rest.substr(0, dot));
    const bool isIndex = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (node->is_array()) {
      std::size_t index = 0;
      const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), index);
      if (!isIndex || error != std::errc() || end != key.data() + key.size() || index >= node->size()) {
        throw SceneError(fmt::format("--set {}: {} is a list of {} entries, numbered 0 to {}; '{}' is none of them (--set "
                                     "changes an entry, it cannot add one: add it in the scene file)", assignment, walked,
                                     node->size(), static_cast<long>(node->size()) - 1, key),
                         SceneError::Kind::UnknownKey);
      }
      if (dot == std::string_view::npos) {
        (*node)[index] = std::move(value);
        return;
      }
      node = &(*node)[index];
    } else if (node->is_object()) {
      if (isIndex && node != &document && node->empty()) {
        throw SceneError(fmt::format("--set {}: the scene has no {} list; --set changes an entry of a list but cannot make "
                                     "one: write {} in the scene file", assignment, walked, walked),
                         SceneError::Kind::UnknownKey);
      }
      if (dot == std::string_view::npos) {
        (*node)[key] = std::move(value);
        return;
      }
      node = &(*node)[key];
      if (node->is_null()) *node = nlohmann::json::object();
    } else {
      throw SceneError(fmt::format("--set {}: {} is {}, which has no field '{}'", assignment, walked,
                                   describeJson(*node), key),
                       SceneError::Kind::UnknownKey);
    }
    walked += (walked.empty() ? "" : ".") + key;
    rest = rest.substr(dot + 1);
  }
}

nlohmann::json builtInDefaultScene() {
  return {
      {"name", "coinroll"},
      {"coin", {{"shape", "disk"}, {"radius", 0.0375}, {"mass", 0.4}}},
      {"initial", {{"theta", 15}, {"omega_Y", 2.0}, {"omega_Z", 16}}},
      {"duration", 6},
      // The coin's circle (0.39 m across, centred 0.18 m ahead of its start) fills the frame from
      // 28 deg above the floor, so the coin is about a third of the frame tall on the near side;
      // the automatic framing would fit the circle's bounding box and show the coin at half that.
      {"render", {{"time_scale", 0.5}, {"camera", {{"eye", {-0.166, 0.258, -0.273}}, {"target", {0, 0, 0.183}}}}}},
  };
}

}  // namespace coinroll::scene
