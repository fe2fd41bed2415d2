// The bad-input table's scene refusals, in process: every case of tests/cli/bad_inputs.py that is
// a scene file (and --set overrides) in and exit 2 out goes through the calls `coinroll simulate`
// makes before it writes anything (read, override, parse, build the simulation) and must be
// refused with the table's message. The table stays the one source (the build exports its cases);
// this runs them in a second under AddressSanitizer, where starting the program for each would
// take minutes.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "pipeline/simulation.h"
#include "scene/json_reader.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"

namespace coinroll {
namespace {

struct BadScene {
  std::string id;
  std::string bytes;  // the scene file exactly as the table writes it
  std::vector<std::string> overrides;
  std::string message;
  std::string orMessage;  // the other designed wording, when the table allows one
};

void PrintTo(const BadScene& c, std::ostream* out) { *out << c.id; }

std::vector<BadScene> tableCases() {
  std::ifstream file(COINROLL_BAD_SCENE_CASES);
  if (!file)
    throw std::runtime_error("cannot open " COINROLL_BAD_SCENE_CASES "; the build exports it from bad_inputs.py");
  std::vector<BadScene> cases;
  for (const nlohmann::json& entry : nlohmann::json::parse(file)) {
    const std::string hex = entry.at("scene_hex");
    std::string bytes;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
      bytes.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
    cases.push_back({entry.at("id"), bytes, entry.at("overrides"), entry.at("message"), entry.at("or_message")});
  }
  return cases;
}

class BadSceneTest : public testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, IsRefusedBeforeAnythingRunsWithTheTablesMessage) {
  const BadScene& c = GetParam();
  // Named by the process too, as tests/support/scratch_dir.h names its directories: two builds'
  // suites run at once on one machine (CI beside the mutation check) must not share one.
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("coinroll_bad_scene_" + c.id + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  const std::filesystem::path scenePath = directory / "scene.json";
  std::ofstream(scenePath, std::ios::binary) << c.bytes;

  std::string refusal = "accepted";
  try {
    nlohmann::json document = scene::readSceneDocument(scenePath);
    for (const std::string& assignment : c.overrides) scene::applyOverride(document, assignment);
    pipeline::buildSimulation(scene::parseScene(document, scenePath.string()));
  } catch (const scene::SceneError& e) {  // what the program answers with exit 2, printed as it prints it
    refusal = scene::printable(e.what());
  }
  std::filesystem::remove_all(directory);
  const bool named = refusal.find(c.message) != std::string::npos ||
                     (!c.orMessage.empty() && refusal.find(c.orMessage) != std::string::npos);
  EXPECT_TRUE(named) << c.id << ": expected \"" << c.message << "\", got \"" << refusal << "\"";
}

// Named by the table's case id, so a failure reads as the row to look up in docs/bad_inputs.md.
std::string caseName(const testing::TestParamInfo<BadScene>& param) {
  std::string name;
  for (const char ch : param.param.id) name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Table, BadSceneTest, testing::ValuesIn(tableCases()), caseName);

}  // namespace
}  // namespace coinroll
