// README "Scene format" against the code: each default and limit the table gives is read from the
// README and compared with the one definition the loader uses, so neither can change alone.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "integrate/solver_config.h"
#include "render/render_settings.h"
#include "scene/scene_config.h"
#include "video/video_options.h"

namespace coinroll::scene {
namespace {

struct Row {
  std::string unit, fallback, rule;  // the table's columns after the key
};

// The scene table's rows by their key cell ("`solver.dt`"), cells trimmed.
std::map<std::string, Row> sceneTable() {
  std::ifstream in(std::string(COINROLL_SOURCE_DIR) + "/README.md");
  std::map<std::string, Row> rows;
  const auto trim = [](std::string text) {
    text.erase(0, text.find_first_not_of(' '));
    text.erase(text.find_last_not_of(' ') + 1);
    return text;
  };
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("| `")) continue;
    std::vector<std::string> cells;
    std::size_t from = 1;
    // Escaped bars (\|) belong to a cell.
    for (std::size_t at = from; (at = line.find('|', at)) != std::string::npos; ++at) {
      if (line[at - 1] == '\\') continue;
      cells.push_back(trim(line.substr(from, at - from)));
      from = at + 1;
    }
    if (cells.size() == 4) rows[cells[0]] = {cells[1], cells[2], cells[3]};
  }
  return rows;
}

const Row& row(const std::string& key) {
  static const std::map<std::string, Row> table = sceneTable();
  const auto found = table.find(key);
  if (found == table.end()) throw std::runtime_error("README.md's scene table has no row " + key);
  return found->second;
}

// The numbers of a cell like "1e-10, 1e-12" or "35, 30".
std::vector<double> numbers(const std::string& cell) {
  std::vector<double> values;
  std::stringstream in(cell);
  for (std::string item; std::getline(in, item, ',');) values.push_back(std::stod(item));
  return values;
}

// The two numbers of `pattern`'s groups in `cell` ("in \\[(.+), (.+)\\]").
std::pair<double, double> range(const std::string& cell, const std::string& pattern) {
  std::smatch match;
  if (!std::regex_search(cell, match, std::regex(pattern))) throw std::runtime_error("no " + pattern + " in: " + cell);
  return {std::stod(match[1]), std::stod(match[2])};
}

TEST(ReadmeSceneTable, SolverDefaultsAndRangesAreTheIntegratorsOwn) {
  const SolverSpec solver;
  EXPECT_EQ(row("`solver.method`").fallback, fmt::format("`{}`", integrate::nameOf(solver.method)));
  std::string methods;
  for (const std::string_view name : integrate::methodNames()) methods += fmt::format("{}`{}`", methods.empty() ? "" : ", ", name);
  EXPECT_EQ(row("`solver.method`").rule, methods);
  EXPECT_EQ(numbers(row("`solver.rtol`, `solver.atol`").fallback), (std::vector{solver.rtol, solver.atol}));
  const std::string& tolerances = row("`solver.rtol`, `solver.atol`").rule;
  EXPECT_EQ(range(tolerances, R"(rtol in \[([^,]+), ([^\]]+)\])"), (std::pair(integrate::kMinRtol, integrate::kMaxRtol)));
  EXPECT_EQ(range(tolerances, R"(atol in \((0), ([^\]]+)\])").second, integrate::kMaxAtol);
  EXPECT_EQ(numbers(row("`solver.dt`").fallback), std::vector{solver.dt});
  EXPECT_EQ(range(row("`solver.dt`").rule, R"(in \[([^,]+), ([^\]]+)\])"), (std::pair(integrate::kMinDt, integrate::kMaxDt)));
}

TEST(ReadmeSceneTable, RenderDefaultsAndRangesAreTheLoadersOwn) {
  const RenderSpec render;
  EXPECT_EQ(numbers(row("`render.width`, `height`").fallback),
            (std::vector<double>{static_cast<double>(render.picture.width), static_cast<double>(render.picture.height)}));
  EXPECT_EQ(range(row("`render.width`, `height`").rule, R"((\d+)\.\.(\d+))"),
            (std::pair<double, double>(render::kMinImageSide, render::kMaxImageSide)));
  EXPECT_EQ(numbers(row("`render.fps`").fallback), std::vector<double>{static_cast<double>(render.fps)});
  EXPECT_EQ(range(row("`render.fps`").rule, R"((\d+)\.\.(\d+))"), (std::pair<double, double>(1, kMaxFps)));
  EXPECT_EQ(numbers(row("`render.msaa`").fallback), std::vector<double>{static_cast<double>(render.picture.msaa)});
  EXPECT_NE(row("`render.msaa`").rule.find(fmt::format("{}", fmt::join(render::kMsaaSampleCounts, ", "))), std::string::npos);
  EXPECT_EQ(numbers(row("`render.time_scale`").fallback), std::vector{render.timeScale});
  EXPECT_EQ(numbers(row("`render.camera.fov`, `elevation`").fallback),
            (std::vector{render.camera.fovDegrees, render.camera.elevationDegrees}));
  EXPECT_EQ(numbers(row("`render.camera.orbit_period`").fallback), std::vector{render.camera.orbitPeriod});
  EXPECT_EQ(row("`render.camera.mode`").fallback, fmt::format("`\"{}\"`", kCameraModeNames[static_cast<std::size_t>(render.camera.mode)]));
  EXPECT_EQ(row("`render.video`").fallback, fmt::format("`{{\"crf\": {}, \"preset\": \"{}\", \"threads\": {}}}`", render.video.crf,
                                                         render.video.preset, render.video.threads));
  const std::string& videoRule = row("`render.video`").rule;
  EXPECT_EQ(range(videoRule, R"(crf (\d+)\.\.(\d+))"), (std::pair<double, double>(0, video::kMaxCrf)));
  EXPECT_EQ(range(videoRule, R"(threads (\d+)\.\.(\d+))"), (std::pair<double, double>(1, video::kMaxX264Threads)));
}

TEST(ReadmeSceneTable, TopLevelDefaultsAreTheLoadersOwn) {
  const SceneConfig scene;
  EXPECT_EQ(row("`name`").fallback, fmt::format("`\"{}\"`", scene.name));
  EXPECT_EQ(numbers(row("`gravity`").fallback), std::vector{scene.gravity});
  EXPECT_EQ(row("`on_invalid`").fallback, "`\"stop\"`");
  EXPECT_EQ(scene.onInvalid, OnInvalid::Stop);
}

}  // namespace
}  // namespace coinroll::scene
