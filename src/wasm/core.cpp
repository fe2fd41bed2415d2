// The core's entry point for JavaScript (docs/web.md): `coinroll simulate` and `coinroll steady` as
// calls. simulate runs the command's run (pipeline::simulateScene) on the scene read as the command
// reads it (cli/command_support.cpp loadSceneDocument), keeping the rows as the CSV's text or as
// columns of doubles; steady makes the calls its command makes (cli/commands.cpp runSteady), in the
// command's order. So the CSV is the command's CSV, the steady report the command's numbers and a
// refused scene the command's message. src/wasm/core_api.js wraps them in the module's documented
// functions.

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <limits>
#include <new>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "physics/steady.h"
#include "pipeline/cancelled.h"
#include "pipeline/simulation.h"
#include "pipeline/scene_run.h"
#include "pipeline/trajectory_csv.h"
#include "pipeline/visual_track.h"
#include "render/camera.h"
#include "render/floor_tile.h"
#include "render/theme.h"
#include "scene/json_reader.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"

namespace coinroll::wasm {

namespace {

using emscripten::val;

constexpr double kDegreesPerRadian = 180 / std::numbers::pi;

// A refusal of the request (sample step, row limit, a bad request the run finds), as the command's
// UsageError: exit 2.
class BadRequest : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Tells a page how far a run is, and lets it stop the run: `progress(rowsWritten, rowsExpected)`
// after every `every` rows and after the last; returning false sets the run's cancel flag, which
// the run checks before its next sample.
class Progress {
 public:
  Progress(val callback, long expectedRows, std::atomic<bool>& cancel)
      : callback_(std::move(callback)),
        expected_(expectedRows),
        cancel_(cancel),
        every_(std::max(1L, expectedRows / kCalls)) {}

  void row() {
    if (++rows_ % every_ == 0) report();
  }
  void finish() { report(); }

 private:
  // Often enough for a smooth bar, seldom enough that the calls into JavaScript cost nothing.
  static constexpr long kCalls = 200;

  void report() {
    if (callback_.isUndefined() || rows_ == reported_) return;
    reported_ = rows_;
    if (callback_(static_cast<double>(rows_), static_cast<double>(expected_)).strictlyEquals(val(false)))
      cancel_ = true;
  }

  val callback_;
  long expected_;
  std::atomic<bool>& cancel_;
  long every_;
  long rows_ = 0;
  long reported_ = -1;
};

// Bytes or doubles copied out of the module's memory (slice) into a typed array of JavaScript's own.
template <class T>
val copiedOut(std::span<const T> values) {
  return val(emscripten::typed_memory_view(values.size(), values.data())).call<val>("slice");
}

val stringArray(const std::vector<std::string>& strings) {
  val array = val::array();
  for (const std::string& s : strings) array.call<void>("push", s);
  return array;
}

// What a run gives besides its rows: the end, the events in time order, the singular time, the
// step statistics and the command's stderr report.
val runResult(const pipeline::SceneTable& table) {
  const pipeline::TrajectoryReport& result = table.run;
  val out = val::object();
  out.set("rows", static_cast<double>(result.rows));
  val end = val::object();
  end.set("event", std::string(table.end.event));
  end.set("time", table.end.time);
  end.set("description", table.end.description);
  out.set("end", end);

  val events = val::array();
  for (const pipeline::RunMark& mark : table.marks) {
    val event = val::object();
    event.set("kind", std::string(mark.kind));
    event.set("name", std::string(mark.name));
    event.set("time", mark.time);
    event.set("description", mark.description);
    events.call<void>("push", event);
  }
  out.set("events", events);
  // The impacts' times, s ("flight": true): the page slows down at each (render.time_remap.impact).
  std::vector<double> impactTimes;
  for (const pipeline::ImpactRecord& impact : result.impacts) impactTimes.push_back(impact.t);
  out.set("impacts", copiedOut(std::span<const double>(impactTimes)));

  if (const auto& e = result.singularTime) {
    val singular = val::object();
    singular.set("t0", e->t0);
    singular.set("gamma", e->gamma);
    singular.set("fitFrom", e->fitFrom);
    singular.set("samples", e->samples);
    out.set("singularTime", singular);
  } else {
    out.set("singularTime", val::null());
  }
  val stats = val::object();
  stats.set("acceptedSteps", static_cast<double>(result.stats.acceptedSteps));
  stats.set("rejectedSteps", static_cast<double>(result.stats.rejectedSteps));
  stats.set("rhsEvaluations", static_cast<double>(result.stats.rhsEvaluations));
  out.set("stats", stats);

  // All the command prints on stderr: the notes before the run, then its report.
  std::vector<std::string> report = table.start.notes;
  report.insert(report.end(), table.report.begin(), table.report.end());
  out.set("report", stringArray(report));
  return out;
}

val failure(std::string_view kind, int exitCode, const std::string& message) {
  val error = val::object();
  error.set("kind", std::string(kind));
  error.set("exitCode", exitCode);
  // As the command prints it after "coinroll: error: ".
  error.set("message", scene::printable(message));
  val out = val::object();
  out.set("error", error);
  return out;
}

// The scene document as the command reads it (cli/command_support.cpp loadSceneDocument): the
// file's text or the built-in scene, `initial` replaced where a steady state is asked for, then the
// overrides. The name is the one messages give the scene.
std::pair<nlohmann::json, std::string> sceneDocument(const std::string& scene, bool hasScene, val overrides,
                                                     const std::string& sourceName,
                                                     const std::optional<nlohmann::json>& initial = std::nullopt) {
  nlohmann::json document = hasScene ? scene::parseSceneText(scene, sourceName) : scene::builtInDefaultScene();
  scene::applyOverrides(document, emscripten::vecFromJSArray<std::string>(overrides), initial);
  return {std::move(document), hasScene ? sourceName : "built-in default scene"};
}

// Texts as one buffer of UTF-8, each ended by a NUL, for core_api.js to decode at once and split:
// thousands of std::string conversions by embind would walk them a byte at a time.
val textsOut(const std::vector<std::string>& texts) {
  std::string bytes;
  for (const std::string& text : texts) bytes.append(text).push_back('\0');
  return copiedOut(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}

// The visual track (pipeline/visual_track.h) as typed arrays: the coin's triangles (position and
// normal, three floats a vertex; part, one) and its radii, per row the camera (eye, target and up,
// three floats a row; the vertical field of view in degrees, one) and the overlay's text, and the
// clip's clock (each frame's simulated time and playback rate, at fps frames per second of video).
val visualOut(const pipeline::VisualTrack& track, const render::CoinShape& shape) {
  std::vector<float> position, normal, part;
  for (const render::CoinVertex& v : track.coin) {
    position.insert(position.end(), {v.position.x, v.position.y, v.position.z});
    normal.insert(normal.end(), {v.normal.x, v.normal.y, v.normal.z});
    part.push_back(v.part);
  }
  val coin = val::object();
  coin.set("position", copiedOut(std::span<const float>(position)));
  coin.set("normal", copiedOut(std::span<const float>(normal)));
  coin.set("part", copiedOut(std::span<const float>(part)));
  val out = val::object();
  out.set("coin", coin);
  // m: the coin's outer radius, and the face's to the fillet, across which the face's picture lies.
  out.set("coinRadius", static_cast<double>(shape.radius));
  out.set("faceRadius", static_cast<double>(shape.radius - shape.edgeRadius));
  std::vector<float> eye, target, up, fov;
  for (const render::CameraView& camera : track.cameras) {
    const glm::vec3 cameraUp = render::upOf(camera);
    eye.insert(eye.end(), {camera.eye.x, camera.eye.y, camera.eye.z});
    target.insert(target.end(), {camera.target.x, camera.target.y, camera.target.z});
    up.insert(up.end(), {cameraUp.x, cameraUp.y, cameraUp.z});
    fov.push_back(camera.fovYDegrees);
  }
  val cameras = val::object();
  cameras.set("eye", copiedOut(std::span<const float>(eye)));
  cameras.set("target", copiedOut(std::span<const float>(target)));
  cameras.set("up", copiedOut(std::span<const float>(up)));
  cameras.set("fov", copiedOut(std::span<const float>(fov)));
  out.set("cameras", cameras);
  out.set("overlaySiBytes", textsOut(track.overlaySi));
  out.set("overlaySeedBytes", textsOut(track.overlaySeed));
  val clock = val::object();
  clock.set("fps", track.clock.fps);
  clock.set("times", copiedOut(std::span<const double>(track.clock.times)));
  clock.set("playbackRates", copiedOut(std::span<const double>(track.clock.playbackRates)));
  clock.set("simulatedFrames", static_cast<double>(track.clock.simulatedFrames));
  // s of video a clip holds its landing (and a page its end, before it plays again).
  clock.set("holdSeconds", pipeline::kLandingHoldSeconds);
  out.set("clock", clock);
  return out;
}

val floats(std::initializer_list<float> values) {
  return copiedOut(std::span<const float>(values.begin(), values.size()));
}
val rgb(const glm::vec3& c) { return floats({c.r, c.g, c.b}); }

// What the picture is drawn in for render.theme `name` (render/theme.h) besides the shaders: the sky,
// the trace's colours, and the floor's grid tile (`tilePixels` square, RGBA bytes, lit and in sRGB),
// with the tile's and the grid's size in metres.
val picture(const std::string& name, int tilePixels) {
  const render::Theme theme = name == "paper" ? render::Theme::Paper : render::Theme::Classic;
  const render::Palette& palette = render::palette(theme);
  val out = val::object();
  out.set("backgroundSrgb", rgb(palette.backgroundSrgb));
  val trace = val::object();
  trace.set("recentRolling", rgb(palette.trace.recentRolling));
  trace.set("oldRolling", rgb(palette.trace.oldRolling));
  trace.set("recentSliding", rgb(palette.trace.recentSliding));
  trace.set("oldSliding", rgb(palette.trace.oldSliding));
  trace.set("opacity", floats({palette.trace.opacity.x, palette.trace.opacity.y}));
  out.set("trace", trace);
  val floor = val::object();
  floor.set("floor", rgb(palette.floor.floor));
  floor.set("minorLine", rgb(palette.floor.minorLine));
  floor.set("majorLine", rgb(palette.floor.majorLine));
  out.set("floor", floor);
  const image::Image tile = render::floorTile(tilePixels, palette.floor);
  out.set("floorTile", copiedOut(std::span<const std::uint8_t>(tile.rgba)));
  out.set("tilePixels", tilePixels);
  out.set("tileMetres", render::kFloorTileMetres);
  out.set("gridMetres", render::kFloorGridMetres);
  return out;
}

val numberOrNull(const std::optional<double>& value) { return value ? val(*value) : val::null(); }

// `scene`: the scene file's bytes (a JavaScript string arrives as UTF-8); `hasScene` false: the
// built-in default scene, as the command without a scene file. `asColumns`: the rows as one
// Float64Array per column (`names`, `columns`) instead of the CSV's text (`csvBytes`). The result
// holds `error` (kind, exitCode and message, as the command's exit code and message) instead of
// throwing, so no C++ exception crosses into JavaScript; core_api.js throws it.
val simulate(const std::string& scene, bool hasScene, val overrides, const std::string& sourceName, double sampleDt,
             double maxRows, val progressCallback, bool asColumns, bool visual) {
  try {
    const auto [document, name] = sceneDocument(scene, hasScene, std::move(overrides), sourceName);
    const scene::SceneConfig config = scene::parseScene(document, name);
    std::atomic<bool> cancel = false;
    pipeline::SceneRunRequest request;
    // The visual track's rows lie on the renderer's trace grid, whose slow-downs it follows.
    request.sampleDt = visual ? pipeline::traceInterval(config.duration) : sampleDt;
    request.sampleDtName = "sampleDt";
    // Whole rows, as the run writes them, and no more than a long holds.
    const double limit = std::min(std::floor(maxRows), static_cast<double>(std::numeric_limits<long>::max() / 2));
    request.maxRows = static_cast<long>(limit);
    request.maxRowsOption = "maxRows";
    request.cancel = &cancel;
    std::optional<Progress> progress;
    std::vector<std::vector<double>> columns;
    std::string csv;
    pipeline::TrajectoryCsvLine csvLine;
    std::optional<pipeline::VisualTrackBuilder> track;
    const auto begin = [&](const pipeline::RunStart& start) {
      progress.emplace(std::move(progressCallback), start.expectedRows, cancel);
      if (visual) track.emplace(config, *start.model);
      if (asColumns) {
        columns.resize(start.columns.size());
      } else {
        csv = pipeline::trajectoryCsvHeader(start.columns);
      }
    };
    const auto row = [&](std::span<const double> values) {
      if (asColumns) {
        for (std::size_t i = 0; i < values.size(); ++i) columns[i].push_back(values[i]);
      } else {
        csv += csvLine(values);
      }
      progress->row();
    };
    pipeline::SceneTable table;
    std::optional<pipeline::VisualTrack> finished;
    try {
      pipeline::SampleObserver sample;
      if (visual) sample = [&](double t, const pipeline::RunSample& s, bool isRow) { track->add(t, s, isRow); };
      table = pipeline::simulateScene(config, request, {.begin = begin, .row = row, .sample = sample});
      if (track) finished = std::move(*track).finish(&cancel);
    } catch (const std::invalid_argument& e) {  // the sample step, the row or frame limit: the command's exit 2
      throw BadRequest(e.what());
    }
    progress->finish();

    val out = runResult(table);
    out.set("sampleDt", request.sampleDt);
    if (finished) out.set("visual", visualOut(*finished, config.render.picture.coin));
    if (asColumns) {
      val names = val::array();
      val values = val::array();
      for (std::size_t i = 0; i < columns.size(); ++i) {
        names.call<void>("push", std::string(table.start.columns[i]));
        values.call<void>("push", copiedOut(std::span<const double>(columns[i])));
      }
      out.set("names", names);
      out.set("columnValues", values);
    } else {
      // As bytes, for core_api.js to decode with TextDecoder: embind's own std::string conversion
      // walks the text a byte at a time in JavaScript, which took a tenth of a long run.
      out.set("csvBytes", copiedOut(std::span(reinterpret_cast<const std::uint8_t*>(csv.data()), csv.size())));
    }
    return out;
  } catch (const scene::SceneError& e) {
    return failure("scene", 2, e.what());
  } catch (const pipeline::Cancelled&) {
    return failure("cancelled", 1, "cancelled: the progress callback returned false");
  } catch (const BadRequest& e) {
    return failure("request", 2, e.what());
  } catch (const std::bad_alloc&) {
    return failure("failure", 1, "out of memory: the run does not fit in the module's memory; raise sampleDt");
  } catch (const std::exception& e) {
    return failure("failure", 1, e.what());
  }
}

// `coinroll steady` as a call: every number the command prints (cli/commands.cpp runSteady), from
// the same physics::steadyReport, kept as numbers. `kind` "" takes the scene's own steady initial,
// as the command without --kind; `thetaDegrees`, `omega_Z` (undefined: not given) and `branch` (""
// not given) are its --theta, --omega-Z and --branch. Refusals as simulate's: `error`, never thrown.
val steady(const std::string& scene, bool hasScene, val overrides, const std::string& sourceName,
           const std::string& kind, val thetaDegrees, val omega_Z, const std::string& branch) {
  try {
    for (const auto& [option, value] : {std::pair{"theta", thetaDegrees}, std::pair{"omega_Z", omega_Z}}) {
      // JSON has no NaN or infinity: passed on, they would come back as a null the scene names.
      if (!value.isUndefined() && !std::isfinite(value.as<double>()))
        throw BadRequest(fmt::format("{}: must be a finite number, got {}", option, value.as<double>()));
    }
    std::optional<nlohmann::json> initial;
    if (!kind.empty()) {
      initial = nlohmann::json{{"steady", kind}};
      if (!thetaDegrees.isUndefined()) (*initial)["theta"] = thetaDegrees.as<double>();
      if (!omega_Z.isUndefined()) (*initial)["omega_Z"] = omega_Z.as<double>();
      if (!branch.empty()) (*initial)["branch"] = branch;
    } else if (!thetaDegrees.isUndefined() || !omega_Z.isUndefined() || !branch.empty()) {
      throw BadRequest("theta, omega_Z and branch describe a steady state: give kind too");
    }
    const auto [document, name] = sceneDocument(scene, hasScene, std::move(overrides), sourceName, initial);
    const scene::SceneConfig config = scene::parseScene(document, name);
    if (!std::holds_alternative<scene::SteadyInitial>(config.initial)) {
      throw BadRequest(
          "steady: give kind straight|circle|spin-in-place, or a scene whose initial names a steady state");
    }
    const pipeline::Simulation simulation = pipeline::buildSimulation(config);
    const physics::CoinModel& m = simulation.model;
    const physics::CoinState& s = simulation.initial;
    const physics::SteadyReport report = physics::steadyReport(m, s);
    const double rateUnit = report.naturalRate;

    val out = val::object();
    val coin = val::object();
    coin.set("M", m.M);
    coin.set("a", m.a);
    coin.set("g", m.g);
    coin.set("I_X", m.I_X);
    coin.set("I_Z", m.I_Z);
    out.set("coin", coin);
    if (m.rim.thin()) {
      out.set("rim", val::null());
    } else {
      val rim = val::object();
      rim.set("thickness", m.rim.thickness);
      rim.set("edgeRadius", m.rim.edgeRadius);
      rim.set("cornered", !m.rim.fullyRounded());
      rim.set("cornerOffset", m.rim.cornerOffset());
      rim.set("inertia", std::string(config.coin.shape == scene::Shape::Custom ? "custom" : "solid"));
      out.set("rim", rim);
    }
    out.set("naturalRate", rateUnit);
    out.set("criticalSpin", numberOrNull(report.criticalSpin));
    out.set("criticalSpinInNaturalUnits",
            numberOrNull(report.criticalSpin ? std::optional(*report.criticalSpin / rateUnit) : std::nullopt));
    // In scene units, ready to paste into a scene: angles in degrees.
    val state = val::object();
    state.set("theta", s.theta * kDegreesPerRadian);
    state.set("phi", s.phi * kDegreesPerRadian);
    state.set("psi", s.psi * kDegreesPerRadian);
    state.set("omega_X", s.omega_X);
    state.set("omega_Y", s.omega_Y);
    state.set("omega_Z", s.omega_Z);
    state.set("x", s.x);
    state.set("z", s.z);
    out.set("initial", state);
    val natural = val::object();
    natural.set("omega_Y", s.omega_Y / rateUnit);
    natural.set("omega_Z", s.omega_Z / rateUnit);
    out.set("initialInNaturalUnits", natural);
    out.set("precessionRate", report.precessionRate);
    out.set("spinRate", report.spinRate);
    val radii = val::object();
    radii.set("centreOfMass", report.radii.centreOfMass);
    radii.set("contact", report.radii.contact);
    out.set("radii", radii);
    val reaction = val::object();
    reaction.set("N", report.reaction.N);
    reaction.set("F", report.reaction.F);
    out.set("reaction", reaction);
    out.set("frictionNeeded", report.reaction.N > 0 ? report.reaction.F / report.reaction.N : INFINITY);
    out.set("stiffness", report.stiffness);
    out.set("stiffnessInNaturalUnits", report.stiffness / (rateUnit * rateUnit));

    // Small tilt perturbations obey d(theta)'' = -K d(theta): the two eigenvalues are the roots of
    // lambda^2 = -K, +-i sqrt(K) for a wobble, +-sqrt(-K) for a growth.
    const physics::TiltStability& stability = report.stability;
    val verdict = val::object();
    verdict.set("verdict", std::string(physics::verdictName(stability.kind)));
    verdict.set("rate", stability.rate);
    verdict.set("time", stability.time);
    out.set("stability", verdict);
    const bool wobbles = stability.kind == physics::TiltStability::Kind::Stable;
    val eigenvalues = val::array();
    for (const double sign : {1.0, -1.0}) {
      val lambda = val::object();
      lambda.set("re", wobbles ? 0.0 : sign * stability.rate);
      lambda.set("im", wobbles ? sign * stability.rate : 0.0);
      eigenvalues.call<void>("push", lambda);
    }
    out.set("eigenvalues", eigenvalues);

    std::vector<std::string> notes;
    if (!config.effects.empty()) {
      notes.push_back(
          "coinroll: note: the steady state and its stability below are those of the ideal model; the scene's "
          "effects dissipate energy, so with them this state is only where a slowing motion starts");
    }
    out.set("notes", stringArray(notes));
    return out;
  } catch (const scene::SceneError& e) {
    return failure("scene", 2, e.what());
  } catch (const BadRequest& e) {
    return failure("request", 2, e.what());
  } catch (const std::exception& e) {
    return failure("failure", 1, e.what());
  }
}

std::string defaultSceneJson() { return scene::builtInDefaultScene().dump(2) + "\n"; }

}  // namespace

EMSCRIPTEN_BINDINGS(coinroll_core) {
  emscripten::function("coreSimulate", &simulate);
  emscripten::function("coreSteady", &steady);
  emscripten::function("corePicture", &picture);
  emscripten::function("coreDefaultSceneJson", &defaultSceneJson);
  emscripten::constant("coreVersion", std::string(COINROLL_VERSION));
}

}  // namespace coinroll::wasm
