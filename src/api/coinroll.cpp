#include "coinroll/coinroll.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>

#include "integrate/solver_config.h"
#include "pipeline/simulation.h"
#include "pipeline/still.h"
#include "pipeline/trajectory_csv.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"
#include "video/make_sink.h"

namespace coinroll {

struct Scene::Impl {
  scene::SceneConfig config;
};

namespace {

// The library's promise: a bad scene or request is std::invalid_argument, whatever the layer
// below calls it.
template <class Work>
auto translatingErrors(Work&& work) {
  try {
    return work();
  } catch (const scene::SceneError& e) {
    throw std::invalid_argument(e.what());
  }
}

Scene::Impl parsed(nlohmann::json document, const std::vector<std::string>& overrides, std::string_view sourceName) {
  for (const std::string& assignment : overrides) scene::applyOverride(document, assignment);
  return {scene::parseScene(document, sourceName, {.solverMethods = integrate::methodNames()})};
}

}  // namespace

std::string version() { return COINROLL_VERSION; }

Scene Scene::fromFile(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return translatingErrors([&] {
    return Scene(std::make_shared<const Impl>(parsed(scene::readSceneDocument(file), overrides, file.string())));
  });
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
// read back from its text: the shortest round-trip form it prints gives back the same doubles.
Columns simulate(const Scene& scene, double sampleDt) {
  if (!(sampleDt > 0) || !std::isfinite(sampleDt)) {
    throw std::invalid_argument(fmt::format("sampleDt: must be a finite number > 0 s, got {}", sampleDt));
  }
  std::stringstream csv;
  translatingErrors([&] {
    return pipeline::writeTrajectoryCsv(pipeline::buildSimulation(scene.impl().config), sampleDt, csv);
  });
  Columns columns;
  std::string line;
  std::getline(csv, line);
  for (std::stringstream header(line); std::getline(header, line, ',');) columns.names.push_back(line);
  columns.values.resize(columns.names.size());
  while (std::getline(csv, line)) {
    std::size_t column = 0;
    for (std::string_view rest = line; column < columns.names.size(); ++column) {
      const std::string_view field = rest.substr(0, rest.find(','));
      double value = 0;
      std::from_chars(field.data(), field.data() + field.size(), value);
      columns.values[column].push_back(value);
      rest.remove_prefix(std::min(rest.size(), field.size() + 1));
    }
  }
  return columns;
}

Image renderStill(const Scene& scene, double time) {
  pipeline::StillRequest request;
  request.time = time;
  const pipeline::StillPicture picture = translatingErrors([&] { return pipeline::drawStill(scene.impl().config, request); });
  return {.width = picture.image.width, .height = picture.image.height,
          .rgba = std::vector<std::uint8_t>(picture.image.rgba.begin(), picture.image.rgba.end())};
}

void renderVideo(const Scene& scene, const std::filesystem::path& output) {
  translatingErrors([&] {
    const scene::SceneConfig& config = scene.impl().config;
    std::unique_ptr<video::FrameSink> sink = video::makeSinkForPath(output, config.render.mp4Options());
    return pipeline::renderVideo(config, *sink, {});
  });
}

}  // namespace coinroll
