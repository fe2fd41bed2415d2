#include "coinroll/coinroll.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <thread>
#include <utility>
#include <variant>

#include "physics/coin_model.h"
#include "physics/observables.h"
#include "physics/steady.h"
#include "pipeline/cancelled.h"
#include "pipeline/inputs.h"
#include "pipeline/scene_run.h"
#include "pipeline/simulation.h"
#include "pipeline/still.h"
#include "pipeline/sweep.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"
#include "video/make_sink.h"
#include "video/video_kinds.h"

namespace coinroll {

struct Scene::Impl {
  nlohmann::json document;  // with the overrides applied: what a sweep varies
  std::string sourceName;   // names the scene in messages
  scene::SceneConfig config;
  std::optional<std::filesystem::path> file = std::nullopt;  // the scene file, an input no output replaces
};

namespace {

constexpr double kDegreesPerRadian = 180 / std::numbers::pi;

// A call's argument in a message, between two of these: the layers below write whatever name they
// are given for it, and translatingErrors cuts the message there into an ArgumentError, which can
// then name the argument as each door spells it (ArgumentError::naming).
constexpr char kArgumentMark = '\x1f';

std::string marked(std::string_view argument) { return fmt::format("{0}{1}{0}", kArgumentMark, argument); }

// "a \x1fname\x1f b" -> ArgumentError("name", {"a ", " b"}).
ArgumentError argumentErrorFrom(std::string_view message) {
  std::vector<std::string> around;
  std::string argument;
  std::size_t start = 0;
  for (std::size_t piece = 0;; ++piece) {
    const std::size_t end = message.find(kArgumentMark, start);
    const std::string_view text = message.substr(start, end == std::string_view::npos ? end : end - start);
    if (piece % 2 == 0) {
      around.emplace_back(text);
    } else {
      argument = text;
    }
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return ArgumentError(std::move(argument), std::move(around));
}

// The library's promise: a bad scene is SceneError, a bad argument ArgumentError (both
// std::invalid_argument, as any other bad request is) and a cancelled call coinroll::Cancelled,
// whatever the layer below calls them.
template <class Work>
auto translatingErrors(Work&& work) {
  try {
    return work();
  } catch (const scene::SceneError& e) {
    throw SceneError(e.what());
  } catch (const pipeline::Cancelled&) {
    throw Cancelled();
  } catch (const std::invalid_argument& e) {
    if (std::string_view(e.what()).find(kArgumentMark) == std::string_view::npos) throw;
    throw argumentErrorFrom(e.what());
  }
}

std::string joinedAround(const std::vector<std::string>& around, std::string_view argument) {
  std::string message;
  for (std::size_t i = 0; i < around.size(); ++i) {
    if (i > 0) message += argument;
    message += around[i];
  }
  return message;
}

Scene::Impl parsed(nlohmann::json document, const std::vector<std::string>& overrides, std::string_view sourceName) {
  scene::applyOverrides(document, overrides);
  scene::SceneConfig config = scene::parseScene(document, sourceName);
  return {std::move(document), std::string(sourceName), std::move(config)};
}

}  // namespace

std::string version() { return COINROLL_VERSION; }

Cancelled::Cancelled() : std::runtime_error("interrupted") {}

ArgumentError::ArgumentError(std::string argument, std::vector<std::string> around)
    : std::invalid_argument(joinedAround(around, argument)),
      argument_(std::move(argument)),
      around_(std::move(around)) {}

std::string ArgumentError::naming(std::string_view spelling) const { return joinedAround(around_, spelling); }

Scene Scene::fromFile(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    Impl impl = parsed(scene::readSceneDocument(file), overrides, file.string());
    impl.file = file;
    return Scene(std::make_shared<const Impl>(std::move(impl)));
  });
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return Scene::fromFile(file, overrides);
}

Scene Scene::fromJson(std::string_view json, const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    return Scene(
        std::make_shared<const Impl>(parsed(scene::parseSceneText(json, "scene JSON"), overrides, "scene JSON")));
  });
}

Scene Scene::builtInDefault(const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    return Scene(
        std::make_shared<const Impl>(parsed(scene::builtInDefaultScene(), overrides, "built-in default scene")));
  });
}

std::string Scene::name() const { return impl_->config.name; }
double Scene::duration() const { return impl_->config.duration; }
std::optional<std::filesystem::path> Scene::file() const { return impl_->file; }

const std::vector<double>& Columns::operator[](std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return values[i];
  }
  throw std::out_of_range(fmt::format("no column \"{}\" (this scene's columns: {})", name, fmt::join(names, ", ")));
}

// The same rows the CSV writer prints (pipeline/scene_run.h), kept as numbers.
Columns simulate(const Scene& scene, double sampleDt, const std::atomic<bool>* cancel) {
  Columns columns;
  const std::string sampleDtName = marked("sampleDt");
  pipeline::SceneRunRequest request;
  request.sampleDt = sampleDt;
  request.sampleDtName = sampleDtName;
  // The command's limit (the request's default), without its --max-rows: these rows are held in
  // memory, not streamed.
  request.cancel = cancel;
  const auto begin = [&columns](const pipeline::RunStart& start) {
    columns.names.assign(start.columns.begin(), start.columns.end());
    columns.values.resize(start.columns.size());
  };
  const auto row = [&columns](std::span<const double> values) {
    for (std::size_t i = 0; i < values.size(); ++i) columns.values[i].push_back(values[i]);
  };
  const pipeline::SceneTable table = translatingErrors(
      [&] { return pipeline::simulateScene(scene.impl().config, request, {.begin = begin, .row = row}); });
  columns.end = {.event = std::string(table.end.event), .time = table.end.time, .description = table.end.description};
  return columns;
}

Image renderStill(const Scene& scene, double time, const std::atomic<bool>* cancel) {
  pipeline::StillRequest request;
  request.time = time;
  request.timeName = marked("time");
  request.cancel = cancel;
  pipeline::StillPicture picture = translatingErrors([&] { return pipeline::drawStill(scene.impl().config, request); });
  return {.width = picture.image.width, .height = picture.image.height, .rgba = std::move(picture.image.rgba)};
}

void renderVideo(const Scene& scene, const std::filesystem::path& output, const std::atomic<bool>* cancel) {
  translatingErrors([&] {
    // The command's rules for its -o, checked in the same order before any work.
    const std::string outputName = marked("output");
    if (output.empty()) {
      throw std::invalid_argument(
          fmt::format("{}: the file name is empty; give the file to write, e.g. \"clip.mp4\" "
                      "(or \"frame_%05d.png\" for a PNG sequence)",
                      outputName));
    }
    const scene::SceneConfig& config = scene.impl().config;
    const video::VideoOptions encoding = config.render.mp4Options();
    if (const std::optional<video::VideoFormat> format = video::videoFormatOf(output)) {
      video::refuseOutputThatCannotCarry(encoding, *format, "\"audio\": false in the scene's render block");
    }
    const std::vector<std::filesystem::path> inputs = pipeline::inputFiles(scene.impl().file);
    video::refuseOverwritingInput(outputName, output, inputs);
    std::unique_ptr<video::FrameSink> sink = video::makeSinkForPath(output, encoding, inputs);
    pipeline::VideoRunOptions options;
    options.cancel = cancel;
    options.maxFramesOption = {};  // the API has no way to raise the limit
    return pipeline::renderVideo(config, *sink, options);
  });
}

// The report `coinroll steady` prints (physics::steadyReport), returned instead of printed.
SteadyState steady(const Scene& scene) {
  const scene::SceneConfig& config = scene.impl().config;
  if (!std::holds_alternative<scene::SteadyInitial>(config.initial)) {
    throw std::invalid_argument(
        fmt::format("{}: initial: names no steady state; give {{\"steady\": \"straight\" | "
                    "\"circle\" | \"spin-in-place\", ...}}",
                    scene.impl().sourceName));
  }
  const pipeline::Simulation simulation = translatingErrors([&] { return pipeline::buildSimulation(config); });
  const physics::CoinModel& m = simulation.model;
  const physics::CoinState& s = simulation.initial;
  const physics::SteadyReport report = physics::steadyReport(m, s);
  SteadyState state{.mass = m.M,
                    .radius = m.a,
                    .gravity = m.g,
                    .inertiaX = m.I_X,
                    .inertiaZ = m.I_Z,
                    .thickness = m.rim.thickness,
                    .edgeRadius = m.rim.edgeRadius,
                    .naturalRate = report.naturalRate,
                    .criticalSpin = report.criticalSpin,
                    .theta = s.theta * kDegreesPerRadian,
                    .phi = s.phi * kDegreesPerRadian,
                    .psi = s.psi * kDegreesPerRadian,
                    .omega_X = s.omega_X,
                    .omega_Y = s.omega_Y,
                    .omega_Z = s.omega_Z,
                    .x = s.x,
                    .z = s.z,
                    .precessionRate = report.precessionRate,
                    .spinRate = report.spinRate,
                    .centreOfMassRadius = report.radii.centreOfMass,
                    .contactRadius = report.radii.contact,
                    .normalForce = report.reaction.N,
                    .frictionForce = report.reaction.F,
                    .stiffness = report.stiffness,
                    .stability = std::string(physics::verdictName(report.stability.kind))};
  return state;
}

// The points the sweep CSV's rows are written from (pipeline/sweep.h), kept as numbers.
SweepTable sweep(const Scene& scene, const std::vector<std::string>& axes, int threads,
                 const std::atomic<bool>* cancel) {
  if (threads < 0 || threads > 1024) {
    throw std::invalid_argument(fmt::format("threads: must be 1 to 1024 (0: every hardware thread), got {}", threads));
  }
  pipeline::SweepSpec spec{
      .scene = scene.impl().document,
      .sourceName = scene.impl().sourceName,
      .axes = {},
      .shard = {},
      .threads = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())),
      .maxPoints = pipeline::kDefaultMaxPoints};
  for (const std::string& axis : axes) spec.axes.push_back(pipeline::parseGridAxis(axis));
  pipeline::refuseMisnamedAxes(spec);
  const pipeline::SweepIdentity identity = pipeline::sweepIdentity(spec);
  SweepTable table{.columns = {}, .end = {}, .gridPoints = identity.gridPoints, .digest = identity.digest};
  table.columns.names.push_back("point");
  for (const pipeline::GridAxis& axis : spec.axes) table.columns.names.push_back(axis.key);
  for (const char* name : {"t_end", "theta_min", "theta_max", "energy_start", "energy_end", "theta_end"})
    table.columns.names.push_back(name);
  table.columns.values.resize(table.columns.names.size());
  translatingErrors([&] {
    return pipeline::runSweep(
        spec,
        [&table](const pipeline::SweepPoint& point) {
          std::vector<std::vector<double>>& values = table.columns.values;
          std::size_t column = 0;
          values[column++].push_back(static_cast<double>(point.point));
          for (const double v : point.values) values[column++].push_back(v);
          for (const double v :
               {point.tEnd, point.thetaMin, point.thetaMax, point.energyStart, point.energyEnd, point.thetaEnd}) {
            values[column++].push_back(v);
          }
          table.end.push_back(point.end);
        },
        {}, cancel);
  });
  return table;
}

}  // namespace coinroll
