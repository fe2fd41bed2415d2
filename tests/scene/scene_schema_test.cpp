// The scene schema against the loader and the documents made from it: every range the table
// states is the one the loader enforces (probed at and just past each bound), every name of an
// enumerated key is taken and no other, every default is accepted, `--set KEY=null` restores the
// default, and docs/scene.md, docs/contract.md and the fuzzer's dictionary agree with the table.

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <variant>

#include "physics/effects.h"
#include "scene/scene_loader.h"
#include "scene/scene_schema.h"

namespace coinroll::scene {
namespace {

// The least scene the loader accepts: every probe below starts from it.
nlohmann::json baseScene() {
  return {{"coin", {{"radius", 0.0375}, {"mass", 0.4}}}, {"initial", nlohmann::json::object()}, {"duration", 1}};
}

// "effects[air_drag].viscosity" -> "effects.0.viscosity", "initial[steady].theta" -> "initial.theta":
// the key as `--set` reaches it.
std::string setPath(std::string_view path) {
  std::string out(path);
  out = std::regex_replace(out, std::regex(R"(effects\[[a-z_]+\])"), "effects.0");
  return std::regex_replace(out, std::regex(R"(initial\[steady\])"), "initial");
}

// The key as messages name it: "effects[0].viscosity", "initial.theta".
std::string messagePath(std::string_view path) {
  std::string out = setPath(path);
  return std::regex_replace(out, std::regex(R"(effects\.0)"), "effects[0]");
}

// The loader's refusal of the base scene with the key's context and `assignments`, or "" when it
// is accepted.
std::string refusal(const schema::Key& key, const std::vector<std::string>& assignments) {
  nlohmann::json document = baseScene();
  try {
    for (const std::string& context : key.onlyWith) applyOverride(document, context);
    for (const std::string& assignment : assignments) applyOverride(document, assignment);
    parseScene(document, "scene.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return {};
}

std::string assignment(const schema::Key& key, const nlohmann::json& value) {
  return fmt::format("{}={}", setPath(key.path), value.dump());
}

// A number as the key takes it: a camera point is three coordinates.
nlohmann::json asValue(const schema::Key& key, double number) {
  if (key.type == schema::Type::Point) return {number, 0, 0};
  if (key.type == schema::Type::Integer) return static_cast<long long>(number);
  return number;
}

bool isAbout(const std::string& message, const schema::Key& key) {
  return message.starts_with(fmt::format("scene.json: {}:", messagePath(key.path)));
}

TEST(SceneSchema, EveryBoundIsTheLoadersOwn) {
  int probed = 0;
  for (const schema::Key& key : schema::keys()) {
    for (const auto& [bound, outward] : {std::pair{key.lower, -1.0}, std::pair{key.upper, +1.0}}) {
      if (!bound) continue;
      const bool integer = key.type == schema::Type::Integer;
      const double inside = bound->inclusive ? bound->value
                            : integer       ? bound->value - outward
                                            : std::nextafter(bound->value, -outward * INFINITY);
      const double outside = !bound->inclusive ? bound->value
                             : integer        ? bound->value + outward
                                              : std::nextafter(bound->value, outward * INFINITY);
      SCOPED_TRACE(fmt::format("{}: inside {}, outside {}", key.path, inside, outside));
      EXPECT_EQ(refusal(key, {assignment(key, asValue(key, inside))}), "");
      const std::string refused = refusal(key, {assignment(key, asValue(key, outside))});
      EXPECT_TRUE(isAbout(refused, key)) << refused;
      ++probed;
    }
  }
  EXPECT_GE(probed, 60);  // the table states ranges for most numbers; a lost bound shows here
}

TEST(SceneSchema, EveryNameIsTakenAndNoOther) {
  for (const schema::Key& key : schema::keys()) {
    if (key.names.empty()) continue;
    SCOPED_TRACE(key.path);
    for (const std::string_view name : key.names) {
      // Another key may then be missing (a custom shape needs its inertia): the name itself is taken.
      const std::string refused = refusal(key, {assignment(key, std::string(name))});
      EXPECT_FALSE(isAbout(refused, key)) << refused;
    }
    EXPECT_TRUE(isAbout(refusal(key, {assignment(key, "no-such-name")}), key));
  }
}

TEST(SceneSchema, EveryDefaultIsAccepted) {
  for (const schema::Key& key : schema::keys()) {
    if (key.defaultText.empty()) continue;
    SCOPED_TRACE(key.path);
    EXPECT_EQ(refusal(key, {assignment(key, nlohmann::json::parse(key.defaultText))}), "");
  }
}

TEST(SceneSchema, EachObjectAllowsTheTablesKeysInItsOrder) {
  const std::string refused = refusal(schema::key("coin.radius"), {"coin.colour=1"});
  EXPECT_EQ(refused, fmt::format("scene.json: coin.colour: unknown key; allowed here: {}",
                                 fmt::join(schema::keysIn("coin"), ", ")));
  EXPECT_EQ(fmt::format("{}", fmt::join(schema::keysIn("render.video"), ", ")), "crf, preset, threads");
}

TEST(SceneSchema, TheEffectTypesAreTheLawsOwnNames) {
  physics::Effect laws[] = {physics::AirDrag{}, physics::RollingResistance{}, physics::SpinFriction{}};
  for (const physics::Effect& law : laws) EXPECT_EQ(physics::typeName(law), schema::kEffectTypeNames[law.index()]);
}

TEST(SceneSchema, SettingNullRestoresTheDefault) {
  nlohmann::json document = baseScene();
  document["render"] = {{"audio", true}, {"fps", 60}};
  document["effects"] = {{{"type", "air_drag"}}, {{"type", "spin_friction"}}};
  applyOverride(document, "render.audio=null");
  applyOverride(document, "effects.0=null");
  applyOverride(document, "solver.method=null");  // nothing there to remove, and no solver block made
  EXPECT_FALSE(document["render"].contains("audio"));
  EXPECT_EQ(document["render"]["fps"], 60);
  EXPECT_EQ(document["effects"], nlohmann::json::parse(R"([{"type": "spin_friction"}])"));
  EXPECT_FALSE(document.contains("solver"));
  EXPECT_FALSE(parseScene(document, "scene.json").render.audio.has_value());
}

std::string readSource(const std::string& relative) {
  std::ifstream in(std::string(COINROLL_SOURCE_DIR) + "/" + relative);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SceneSchema, DocsSceneMdIsTheTable) {
  const std::string page = readSource("docs/scene.md");
  EXPECT_NE(page.find(schema::toMarkdown()), std::string::npos)
      << "docs/scene.md's table is not the schema's: regenerate it with `coinroll schema --markdown`";
}

TEST(SceneSchema, TheFuzzersDictionaryHasEveryKeyAndName) {
  const std::string dictionary = readSource("tests/fuzz/scene.dict");
  std::set<std::string> words;
  for (const schema::Key& key : schema::keys()) {
    words.insert(std::string(key.name()));
    for (const std::string_view name : key.names) words.insert(std::string(name));
  }
  for (const std::string& word : words) {
    EXPECT_NE(dictionary.find(fmt::format("\"\\\"{}\\\"\"", word)), std::string::npos)
        << "tests/fuzz/scene.dict lacks " << word;
  }
}

// docs/contract.md's scene table names keys as "`initial.theta`, `phi`, `psi`": a path, then
// its siblings by name. Each must be a key of the schema, so the contract cannot name a key the program lost.
TEST(SceneSchema, TheContractsSceneTableNamesOnlySchemaKeys) {
  const std::string contract = readSource("docs/contract.md");
  const std::string section =
      contract.substr(contract.find("## 1. The scene file"), contract.find("## 2.") - contract.find("## 1."));
  std::set<std::string> paths;
  for (const schema::Key& key : schema::keys())
    paths.insert(std::regex_replace(key.path, std::regex(R"(\[steady\])"), ""));
  int named = 0;
  std::istringstream lines(section);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("| `")) continue;
    const std::string first = line.substr(2, line.find(" |", 2) - 2);
    std::string block;
    static const std::regex kCode("`([^`]+)`");
    for (std::sregex_iterator it(first.begin(), first.end(), kCode), end; it != end; ++it) {
      std::string name = (*it)[1];
      if (name.find('.') != std::string::npos) block = name.substr(0, name.rfind('.'));
      else if (!block.empty()) name = block + "." + name;
      EXPECT_TRUE(paths.contains(name)) << "docs/contract.md names " << name << ", which the scene schema lacks";
      ++named;
    }
  }
  EXPECT_GE(named, 20);
}

}  // namespace
}  // namespace coinroll::scene
