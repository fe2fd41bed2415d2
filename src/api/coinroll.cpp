#include "coinroll/coinroll.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <thread>
#include <utility>
#include <variant>

#include "physics/coin_model.h"
#include "physics/observables.h"
#include "physics/steady.h"
#include "physics/validity.h"
#include "pipeline/cancelled.h"
#include "pipeline/simulation.h"
#include "pipeline/still.h"
#include "pipeline/sweep.h"
#include "pipeline/trajectory_csv.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"
#include "video/make_sink.h"

namespace coinroll {

struct Scene::Impl {
  nlohmann::json document;  // with the overrides applied: what a sweep varies
  std::string sourceName;   // names the scene in messages
  scene::SceneConfig config;
};

namespace {

constexpr double kDegreesPerRadian = 180 / std::numbers::pi;

// The library's promise: a bad scene is SceneError (a std::invalid_argument, as any other bad
// request is) and a cancelled call
// coinroll::Cancelled, whatever the layer below calls them.
template <class Work>
auto translatingErrors(Work&& work) {
  try {
    return work();
  } catch (const scene::SceneError& e) {
    throw SceneError(e.what());
  } catch (const pipeline::Cancelled&) {
    throw Cancelled();
  }
}

Scene::Impl parsed(nlohmann::json document, const std::vector<std::string>& overrides, std::string_view sourceName) {
  for (const std::string& assignment : overrides) scene::applyOverride(document, assignment);
  scene::SceneConfig config = scene::parseScene(document, sourceName);
  return {std::move(document), std::string(sourceName), std::move(config)};
}

// The fields of one line of the library's CSV: RFC 4180 quoting (the writers put a field with a
// comma or a quote in quotes and never a line break), empty fields kept.
std::vector<std::string> csvFields(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// The writers print doubles in a form that reads back exactly (%.17g or shortest round-trip); an
// empty field (a sweep's failed point) is NaN.
double csvNumber(std::string_view field) {
  double value = std::numeric_limits<double>::quiet_NaN();
  std::from_chars(field.data(), field.data() + field.size(), value);
  return value;
}

}  // namespace

std::string version() { return COINROLL_VERSION; }

Cancelled::Cancelled() : std::runtime_error("interrupted") {}

Scene Scene::fromFile(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    return Scene(std::make_shared<const Impl>(parsed(scene::readSceneDocument(file), overrides, file.string())));
  });
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return Scene::fromFile(file, overrides);
}

Scene Scene::fromJson(std::string_view json, const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    return Scene(std::make_shared<const Impl>(parsed(scene::parseSceneText(json, "scene JSON"), overrides, "scene JSON")));
  });
}

Scene Scene::builtInDefault(const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    return Scene(std::make_shared<const Impl>(parsed(scene::builtInDefaultScene(), overrides, "built-in default scene")));
  });
}

std::string Scene::name() const { return impl_->config.name; }
double Scene::duration() const { return impl_->config.duration; }

const std::vector<double>& Columns::operator[](std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return values[i];
  }
  throw std::out_of_range(fmt::format("no column \"{}\" (this scene's columns: {})", name, fmt::join(names, ", ")));
}

// The CSV writer is the one definition of the columns and of their sampling, so the columns are
// read back from its text: the %.17g it prints gives back the same doubles.
Columns simulate(const Scene& scene, double sampleDt, const std::atomic<bool>* cancel) {
  if (!(sampleDt > 0) || !std::isfinite(sampleDt)) {
    throw std::invalid_argument(fmt::format("sampleDt: must be a finite number > 0 s, got {}", sampleDt));
  }
  std::stringstream csv;
  const pipeline::CsvRunResult result = translatingErrors([&] {
    pipeline::Simulation simulation = pipeline::buildSimulation(scene.impl().config);
    simulation.cancel = cancel;
    return pipeline::writeTrajectoryCsv(simulation, sampleDt, csv);
  });
  Columns columns;
  std::string line;
  std::getline(csv, line);
  for (std::stringstream header(line); std::getline(header, line, ',');) columns.names.push_back(line);
  columns.values.resize(columns.names.size());
  for (std::vector<double>& column : columns.values) column.reserve(static_cast<std::size_t>(result.rows));
  while (std::getline(csv, line)) {
    std::size_t column = 0;
    for (std::string_view rest = line; column < columns.names.size(); ++column) {
      const std::string_view field = rest.substr(0, rest.find(','));
      columns.values[column].push_back(csvNumber(field));
      rest.remove_prefix(std::min(rest.size(), field.size() + 1));
    }
  }
  if (const auto& stop = result.stoppedBy) {
    columns.end = {.event = std::string(physics::eventName(stop->event)), .time = stop->t,
                   .description = pipeline::describeStop(*stop)};
  } else {
    columns.end = {.event = "duration", .time = scene.duration(), .description = {}};
  }
  return columns;
}

Image renderStill(const Scene& scene, double time, const std::atomic<bool>* cancel) {
  pipeline::StillRequest request;
  request.time = time;
  request.cancel = cancel;
  pipeline::StillPicture picture = translatingErrors([&] { return pipeline::drawStill(scene.impl().config, request); });
  return {.width = picture.image.width, .height = picture.image.height, .rgba = std::move(picture.image.rgba)};
}

void renderVideo(const Scene& scene, const std::filesystem::path& output, const std::atomic<bool>* cancel) {
  translatingErrors([&] {
    const scene::SceneConfig& config = scene.impl().config;
    std::unique_ptr<video::FrameSink> sink = video::makeSinkForPath(output, config.render.mp4Options());
    pipeline::VideoRunOptions options;
    options.cancel = cancel;
    return pipeline::renderVideo(config, *sink, options);
  });
}

// The same physics calls as `coinroll steady` (cli/commands.cpp), returned instead of printed.
SteadyState steady(const Scene& scene) {
  const scene::SceneConfig& config = scene.impl().config;
  if (!std::holds_alternative<scene::SteadyInitial>(config.initial)) {
    throw std::invalid_argument(fmt::format("{}: initial: names no steady state; give {{\"steady\": \"straight\" | "
                                            "\"circle\" | \"spin-in-place\", ...}}", scene.impl().sourceName));
  }
  const pipeline::Simulation simulation = translatingErrors([&] { return pipeline::buildSimulation(config); });
  const physics::CoinModel& m = simulation.model;
  const physics::CoinState& s = simulation.initial;
  const physics::CircleRadii radii = physics::circleRadii(m, s);
  const physics::Reaction reaction = physics::reaction(m, s);
  const bool cornered = !m.rim.thin() && !m.rim.fullyRounded();
  SteadyState state{
      .mass = m.M, .radius = m.a, .gravity = m.g, .inertiaX = m.I_X, .inertiaZ = m.I_Z,
      .thickness = m.rim.thickness, .edgeRadius = m.rim.edgeRadius,
      .naturalRate = physics::naturalRate(m),
      .criticalSpin = cornered ? std::nullopt : std::optional(physics::criticalSpin(m)),
      .theta = s.theta * kDegreesPerRadian, .phi = s.phi * kDegreesPerRadian, .psi = s.psi * kDegreesPerRadian,
      .omega_X = s.omega_X, .omega_Y = s.omega_Y, .omega_Z = s.omega_Z, .x = s.x, .z = s.z,
      .precessionRate = physics::precessionRate(s), .spinRate = physics::spinRate(s),
      .centreOfMassRadius = radii.centreOfMass, .contactRadius = radii.contact,
      .normalForce = reaction.N, .frictionForce = reaction.F,
      .stiffness = physics::wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z),
      .stability = {}};
  state.stability = state.stiffness > 0 ? "stable" : state.stiffness < 0 ? "unstable" : "marginal";
  return state;
}

// The sweep's CSV writer is the one definition of its rows, so the table is read back from its
// text, as simulate's columns are.
SweepTable sweep(const Scene& scene, const std::vector<std::string>& axes, int threads, const std::atomic<bool>* cancel) {
  if (threads < 0 || threads > 1024) {
    throw std::invalid_argument(fmt::format("threads: must be 1 to 1024 (0: every hardware thread), got {}", threads));
  }
  pipeline::SweepSpec spec{.scene = scene.impl().document, .sourceName = scene.impl().sourceName,
                           .axes = {}, .shard = {},
                           .threads = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())),
                           .maxPoints = pipeline::kDefaultMaxPoints};
  for (const std::string& axis : axes) spec.axes.push_back(pipeline::parseGridAxis(axis));
  pipeline::refuseMisnamedAxes(spec);
  pipeline::gridPointCount(spec);
  std::stringstream csv;
  translatingErrors([&] { return pipeline::runSweep(spec, csv, {}, cancel); });

  // point, one field per axis, end, five numbers, grid_points, sweep.
  const std::size_t endField = 1 + axes.size(), identityField = endField + 6;
  SweepTable table;
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = csvFields(line);
  for (std::size_t i = 0; i < identityField; ++i) {
    if (i != endField) table.columns.names.push_back(header[i]);
  }
  table.columns.values.resize(table.columns.names.size());
  while (std::getline(csv, line)) {
    const std::vector<std::string> fields = csvFields(line);
    for (std::size_t i = 0, column = 0; i < identityField; ++i) {
      if (i == endField) {
        table.end.push_back(fields[i]);
      } else {
        table.columns.values[column++].push_back(csvNumber(fields[i]));
      }
    }
    table.gridPoints = std::stol(fields[identityField]);
    table.digest = fields[identityField + 1];
  }
  return table;
}

}  // namespace coinroll
