#include "scene/scene_loader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "integrate/solver_config.h"
#include "scene/json_reader.h"
#include "scene/scene_schema.h"

namespace coinroll::scene {

namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

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
template <class Enum>
Enum enumValue(const JsonReader& r, std::string_view key, Enum fallback, std::string_view rule = {}) {
  const std::optional<std::string> name = r.optionalString(key);
  if (!name) return fallback;
  const std::vector<std::string_view>& names = r.spec(key).names;
  const auto found = std::find(names.begin(), names.end(), *name);
  if (found == names.end()) {
    r.fail(key, rule.empty() ? fmt::format("must be {}, got \"{}\"", schema::quotedAlternatives(names), *name)
                             : fmt::format(fmt::runtime(rule), *name));
  }
  return static_cast<Enum>(found - names.begin());
}

double positive(const JsonReader& r, std::string_view key, double value) {
  if (!(value > 0)) r.fail(key, fmt::format("must be > 0, got {}", value));
  return value;
}

// The number at `key` (`fallback` when absent), in the schema's range for it.
double boundedNumber(const JsonReader& r, std::string_view key, double fallback) {
  return r.bounded(key, r.number(key, fallback));
}

// An angle in the file's degrees, in the schema's range, to radians.
double degrees(const JsonReader& r, std::string_view key) { return boundedNumber(r, key, 0) * kRadiansPerDegree; }

// The coin block: its physics into the returned CoinSpec, its shape as drawn into `drawn`.
CoinSpec parseCoin(const JsonReader& top, render::CoinShape& drawn) {
  // `coin` is there: its row makes it required, which the top level's reader enforced.
  const JsonReader r = top.nested(*top.child("coin"), "coin", "coin");
  CoinSpec coin;
  coin.shape = enumValue(r, "shape", coin.shape);

  coin.radius = r.bounded("radius", r.requiredNumber("radius"));
  coin.mass = r.bounded("mass", r.requiredNumber("mass"));
  const double thickness = boundedNumber(r, "thickness", 0.06 * coin.radius);

  coin.innerRadius = r.number("inner_radius", coin.radius);
  if (coin.shape == Shape::Ring && !(coin.innerRadius >= 0 && coin.innerRadius <= coin.radius)) {
    r.fail("inner_radius", fmt::format("must be in [0, radius = {}] m, got {}", coin.radius, coin.innerRadius));
  }
  if (r.has("thickness")) coin.thickness = thickness;
  if (coin.thickness) {
    const double hole = coin.shape == Shape::Ring ? coin.innerRadius : 0.0;
    const double largest = std::min(0.5 * thickness, coin.radius - hole);
    coin.edgeRadius = r.number("edge_radius", largest);
    if (!(coin.edgeRadius >= 0 && coin.edgeRadius <= largest)) {
      // Name the bound that holds; {:.15g}: 0.0375 - 0.037 would print as 0.0005000000000000004.
      const std::string widthBound =
          coin.shape == Shape::Ring
              ? fmt::format(" and radius - inner_radius = {:.15g} m, the ring's width", coin.radius - hole)
          : coin.radius < 0.5 * thickness ? fmt::format(" and radius = {:.15g} m", coin.radius)
                                          : std::string();
      r.fail("edge_radius", fmt::format("must be in [0, {:.15g}] m (at most thickness / 2 = {:.15g} m{}), got {}",
                                        largest, 0.5 * thickness, widthBound, coin.edgeRadius));
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

  if (coin.shape != Shape::Custom) return coin;
  coin.I_X = r.bounded("I_X", r.requiredNumber("I_X"));
  coin.I_Z = r.bounded("I_Z", r.requiredNumber("I_Z"));
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
  if (node->is_object() && node->contains("steady")) {
    // Before the keys: with a steady kind that is not a name, the message is about the kind, not
    // about the explicit start's rates beside it.
    if (const nlohmann::json& kind = node->at("steady"); !kind.is_string()) {
      JsonReader(nlohmann::json::object(), "initial", "", "initial[steady]")
          .fail("steady",
                fmt::format("must be {}, got {}", schema::quotedAlternatives(schema::kSteadyKindNames),
                            describeJson(kind)),
                SceneError::Kind::WrongType);
    }
    const JsonReader r = top.nested(*node, "initial", "initial[steady]");
    SteadyInitial s;
    s.kind = enumValue(r, "steady", s.kind);
    s.theta = degrees(r, "theta");
    s.omega_Z = boundedNumber(r, "omega_Z", 0);
    const std::string branch = r.optionalString("branch").value_or("+");
    if (branch != "+" && branch != "-") r.fail("branch", fmt::format("must be \"+\" or \"-\", got \"{}\"", branch));
    s.branch = branch == "+" ? 1 : -1;
    s.phi = degrees(r, "phi");
    s.psi = degrees(r, "psi");
    s.x = boundedNumber(r, "x", 0);
    s.z = boundedNumber(r, "z", 0);
    return s;
  }
  const JsonReader r = top.nested(*node, "initial", "initial");
  ExplicitInitial e;
  e.theta = degrees(r, "theta");
  e.phi = degrees(r, "phi");
  e.psi = degrees(r, "psi");
  e.omega_X = boundedNumber(r, "omega_X", 0);
  e.omega_Y = boundedNumber(r, "omega_Y", 0);
  e.omega_Z = boundedNumber(r, "omega_Z", 0);
  e.x = boundedNumber(r, "x", 0);
  e.z = boundedNumber(r, "z", 0);
  if (r.has("v_x") || r.has("v_z"))
    e.velocity = std::array<double, 2>{boundedNumber(r, "v_x", 0), boundedNumber(r, "v_z", 0)};
  if (r.has("y")) e.y = boundedNumber(r, "y", 0);
  if (r.has("v_y")) e.v_y = boundedNumber(r, "v_y", 0);
  return e;
}

SolverSpec parseSolver(const JsonReader& top) {
  SolverSpec solver;
  const nlohmann::json* node = top.child("solver");
  if (node == nullptr) return solver;
  const JsonReader r = top.nested(*node, "solver", "solver");
  if (r.has("formulation")) {
    solver.formulation = enumValue(
        r, "formulation", Formulation{},
        fmt::format("unknown formulation \"{{}}\"; available: {}", fmt::join(schema::kFormulationNames, ", ")));
  }
  if (const std::optional<std::string> method = r.optionalString("method")) {
    const std::optional<integrate::Method> known = integrate::methodFromName(*method);
    if (!known) {
      r.fail("method",
             fmt::format("unknown method \"{}\"; available: {}", *method, fmt::join(integrate::methodNames(), ", ")));
    }
    solver.method = *known;
  }
  // The ranges' reasons are given with them in integrate/solver_config.h.
  solver.rtol = boundedNumber(r, "rtol", solver.rtol);
  solver.atol = boundedNumber(r, "atol", solver.atol);
  solver.dt = boundedNumber(r, "dt", solver.dt);
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
  const double lower = r.spec(key).lower->value, upper = r.spec(key).upper->value;
  if (std::any_of(point.begin(), point.end(), [&](double v) { return !(v >= lower && v <= upper); })) {
    r.fail(key, fmt::format("coordinates must be within [{:g}, {:g}] m, got [{}, {}, {}]", lower, upper, point[0],
                            point[1], point[2]));
  }
  return point;
}

CameraSpec parseCamera(const JsonReader& render) {
  CameraSpec camera;
  const nlohmann::json* node = render.child("camera");
  if (node == nullptr) return camera;
  const JsonReader r = render.nested(*node, "render.camera", "render.camera");
  camera.mode = enumValue(r, "mode", camera.mode);
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
      r.fail("target",
             "must not lie straight above or below eye (the picture's up is the floor normal; tilt the view "
             "slightly)");
    }
  }
  camera.fovDegrees = boundedNumber(r, "fov", camera.fovDegrees);
  camera.orbitPeriod = boundedNumber(r, "orbit_period", camera.orbitPeriod);
  camera.elevationDegrees = boundedNumber(r, "elevation", camera.elevationDegrees);
  return camera;
}

std::optional<AudioSpec> parseAudio(const JsonReader& render) {
  const nlohmann::json* node = render.child("audio");
  if (node == nullptr || (node->is_boolean() && !node->get<bool>())) return std::nullopt;
  AudioSpec audio;
  if (node->is_boolean()) return audio;
  if (!node->is_object())
    render.fail("audio", "must be true, false or an object of options, got " + describeJson(*node));
  const JsonReader a = render.nested(*node, "render.audio", "render.audio");
  audio.pitch = enumValue(a, "pitch", audio.pitch, "must be \"video\" (follows slow motion) or \"real\", got \"{}\"");
  audio.timbre = enumValue(a, "timbre", audio.timbre);
  audio.frequencyScale = boundedNumber(a, "frequency_scale", audio.frequencyScale);
  audio.volume = boundedNumber(a, "volume", audio.volume);
  return audio;
}

// render.time_remap.flight or .impact (`key`), when given.
std::optional<EventSlowDown> parseSlowDown(const JsonReader& remap, std::string_view key) {
  const nlohmann::json* node = remap.child(key);
  if (node == nullptr) return std::nullopt;
  const std::string path = fmt::format("render.time_remap.{}", key);
  const JsonReader r = remap.nested(*node, path, path);
  EventSlowDown slowDown;
  slowDown.slow = boundedNumber(r, "slow", slowDown.slow);
  slowDown.window = boundedNumber(r, "window", slowDown.window);
  return slowDown;
}

RenderSpec parseRender(const JsonReader& top) {
  RenderSpec render;
  const nlohmann::json* node = top.child("render");
  if (node == nullptr) return render;
  const JsonReader r = top.nested(*node, "render", "render");
  render::RenderSettings& picture = render.picture;
  for (auto [key, field] : {std::pair{"width", &picture.width}, std::pair{"height", &picture.height}}) {
    *field = r.integer(key, *field);
    if (schema::rangeViolation(r.spec(key), *field) != "" || *field % 2 != 0) {
      r.fail(key, fmt::format("must be an even number of pixels in [{}, {}] (H.264 yuv420p needs even sizes), got {}",
                              r.spec(key).lower->value, r.spec(key).upper->value, *field));
    }
  }
  render.fps = static_cast<int>(r.bounded("fps", r.integer("fps", render.fps)));
  picture.antialiasing = enumValue(r, "antialiasing", picture.antialiasing);
  picture.msaa = r.integer("msaa", picture.msaa);
  if (!render::isMsaaSampleCount(picture.msaa)) {
    r.fail("msaa",
           fmt::format("must be {} samples, got {}",
                       alternatives(render::kMsaaSampleCounts, [](int n) { return std::to_string(n); }), picture.msaa));
  }
  render.timeScale = boundedNumber(r, "time_scale", render.timeScale);
  if (const nlohmann::json* remap = r.child("time_remap")) {
    const JsonReader m = r.nested(*remap, "render.time_remap", "render.time_remap");
    if (m.has("spin_rate") || m.has("precession_rate")) {
      const std::string_view key = m.has("spin_rate") ? "spin_rate" : "precession_rate";
      const double limit = m.number(key, 0);
      if (!schema::rangeViolation(m.spec(key), limit).empty()) {
        m.fail(key, fmt::format("must be a rate > {:g} {}, got {}", m.spec(key).lower->value, m.spec(key).unit, limit));
      }
      const double growth = boundedNumber(m, "growth", 0);
      render.timeRemap = TimeRemap{.rate = key == "spin_rate" ? TimeRemap::Rate::Spin : TimeRemap::Rate::Precession,
                                   .limit = limit,
                                   .growth = growth};
    }
    render.flightSlowDown = parseSlowDown(m, "flight");
    render.impactSlowDown = parseSlowDown(m, "impact");
  }
  render.camera = parseCamera(r);
  render.trace = r.boolean("trace", render.trace);
  render.hud = r.boolean("hud", render.hud);
  if (const nlohmann::json* video = r.child("video")) {
    const JsonReader v = r.nested(*video, "render.video", "render.video");
    video::X264Options& x264 = render.video;
    x264.crf = static_cast<int>(v.bounded("crf", v.integer("crf", x264.crf)));
    x264.preset = v.optionalString("preset").value_or(x264.preset);
    if (const std::vector<std::string_view>& presets = v.spec("preset").names;
        std::find(presets.begin(), presets.end(), x264.preset) == presets.end()) {
      v.fail("preset", fmt::format("must be one of {}, got \"{}\"", fmt::join(presets, ", "), x264.preset));
    }
    x264.threads = static_cast<int>(v.bounded("threads", v.integer("threads", x264.threads)));
  }
  render.audio = parseAudio(r);
  picture.transparentBackground =
      enumValue(r, "background", 0, "expected \"opaque\" or \"transparent\", got \"{}\"") == 1;
  render.provenance = r.boolean("provenance", render.provenance);
  picture.theme = enumValue(r, "theme", picture.theme);
  const schema::Key& bar = r.spec("scale_bar");
  const std::string scaleBarRule = fmt::format("must be true, false or a length in ({:g}, {:g}] {}, got ",
                                               bar.lower->value, bar.upper->value, bar.unit);
  if (const nlohmann::json* given = r.child("scale_bar"); given != nullptr && given->is_number()) {
    const double metres = r.number("scale_bar", 0);
    if (!schema::rangeViolation(bar, metres).empty()) r.fail("scale_bar", scaleBarRule + describeJson(*given));
    picture.scaleBar = {.shown = true, .metres = static_cast<float>(metres)};
  } else if (given != nullptr && !given->is_boolean()) {
    r.fail("scale_bar", scaleBarRule + describeJson(*given), SceneError::Kind::WrongType);
  } else {
    picture.scaleBar.shown = r.boolean("scale_bar", picture.scaleBar.shown);
  }
  return render;
}

// One entry of "effects" (docs/euler_disk.md §2); defaults are the laws' own member initializers.
physics::Effect parseEffect(const JsonReader& top, const nlohmann::json& node, const std::string& path) {
  if (!node.is_object() || !node.contains("type") || !node["type"].is_string()) {
    throw SceneError(fmt::format("{}: must be an object with a \"type\": {}, got {}", path,
                                 schema::quotedAlternatives(schema::kEffectTypeNames), describeJson(node)),
                     node.is_object() ? SceneError::Kind::BadValue : SceneError::Kind::WrongType);
  }
  const std::string type = node["type"].get<std::string>();
  if (type == "air_drag") {
    const JsonReader r = top.nested(node, path, "effects[air_drag]");
    physics::AirDrag law;
    law.model = enumValue(r, "model", law.model);
    // Air is 1.8e-5 Pa s; the bound admits glycerine and stops overflow in the couple. A value
    // at or below 0 is told the lower bound alone, as every positive quantity is.
    law.viscosity = r.bounded("viscosity", positive(r, "viscosity", r.number("viscosity", law.viscosity)));
    law.density = r.bounded("density", positive(r, "density", r.number("density", law.density)));
    return law;
  }
  if (type == "rolling_resistance") {
    const JsonReader r = top.nested(node, path, "effects[rolling_resistance]");
    physics::RollingResistance law;
    law.length = boundedNumber(r, "length", law.length);
    law.loadExponent = boundedNumber(r, "load_exponent", law.loadExponent);
    law.rateExponent = boundedNumber(r, "rate_exponent", law.rateExponent);
    return law;
  }
  if (type == "spin_friction") {
    const JsonReader r = top.nested(node, path, "effects[spin_friction]");
    physics::SpinFriction law;
    law.length = boundedNumber(r, "length", law.length);
    return law;
  }
  throw SceneError(
      fmt::format("{}.type: must be {}, got \"{}\"", path, schema::quotedAlternatives(schema::kEffectTypeNames), type));
}

// Rolling resistance and pivoting friction are couples N * length whose lever arm lies inside the
// contact patch, so a length at or past the coin's radius has no meaning (and a huge one only
// stalls the integrator).
void refuseLeverArmsPastTheRim(const std::vector<physics::Effect>& effects, double radius) {
  for (std::size_t i = 0; i < effects.size(); ++i) {
    double length = 0;
    if (const auto* rolling = std::get_if<physics::RollingResistance>(&effects[i]))
      length = rolling->length;
    else if (const auto* pivoting = std::get_if<physics::SpinFriction>(&effects[i]))
      length = pivoting->length;
    if (!(length < radius)) {
      throw SceneError(
          fmt::format("effects[{}].length: must be below coin.radius = {} m (the couple's lever arm lies "
                      "inside the contact patch), got {}",
                      i, radius, length));
    }
  }
}

std::vector<physics::Effect> parseEffects(const JsonReader& top) {
  const nlohmann::json* node = top.child("effects");
  if (node == nullptr) return {};
  if (!node->is_array())
    top.fail("effects", "must be a list of effects, e.g. [{\"type\": \"air_drag\"}], got " + describeJson(*node),
             SceneError::Kind::WrongType);
  std::vector<physics::Effect> effects;
  for (std::size_t i = 0; i < node->size(); ++i) {
    const std::string path = fmt::format("effects[{}]", i);
    physics::Effect effect = parseEffect(top, (*node)[i], path);
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

}  // namespace

SceneConfig parseScene(const nlohmann::json& document, std::string_view sourceName) {
  try {
    const JsonReader top(document, "", sourceName, "");
    SceneConfig scene;
    scene.name = top.optionalString("name").value_or(scene.name);
    render::CoinShape drawnCoin;
    scene.coin = parseCoin(top, drawnCoin);
    scene.gravity = boundedNumber(top, "gravity", scene.gravity);
    scene.friction = top.optionalNumber("friction");
    if (scene.friction) top.bounded("friction", *scene.friction);
    scene.frictionStatic = top.optionalNumber("friction_static");
    if (scene.frictionStatic && !(*scene.frictionStatic >= *scene.friction && std::isfinite(*scene.frictionStatic))) {
      top.fail("friction_static", fmt::format("must be >= friction = {} (static friction is at least kinetic), got {}",
                                              *scene.friction, *scene.frictionStatic));
    }
    scene.sliding = top.boolean("sliding", false);
    scene.flight = top.boolean("flight", false);
    if (scene.flight) {
      scene.restitution = top.bounded("restitution", top.requiredNumber("restitution"));
      if (top.has("impact_friction")) scene.impactFriction = boundedNumber(top, "impact_friction", 0);
      scene.stopWhenDecided = top.boolean("stop_when_decided", false);
    }
    scene.initial = parseInitial(top);
    scene.duration = top.bounded("duration", top.requiredNumber("duration"));
    scene.solver = parseSolver(top);
    // A fixed-step run's step count is known now; the integrator would only find it after hours.
    if (!integrate::isAdaptive(scene.solver.method)) {
      const double steps = scene.duration / scene.solver.dt;
      if (const long maxSteps = integrate::SolverConfig{}.maxSteps; steps > static_cast<double>(maxSteps)) {
        throw SceneError(
            fmt::format("solver.dt: duration / dt = {:.3g} steps of {}, more than the {} a run may take; "
                        "raise solver.dt, shorten the duration or use an adaptive method (dop853)",
                        steps, integrate::nameOf(scene.solver.method), maxSteps));
      }
    }
    scene.effects = parseEffects(top);
    refuseLeverArmsPastTheRim(scene.effects, scene.coin.radius);
    scene.onInvalid = enumValue(top, "on_invalid", scene.onInvalid);
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

SceneConfig loadScene(const std::filesystem::path& file, std::span<const std::string> overrides) {
  nlohmann::json document = readSceneDocument(file);
  applyOverrides(document, overrides);
  return parseScene(document, file.string());
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
