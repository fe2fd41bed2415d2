// The scene schema against the loader and the documents made from it: every range the table
// states is the one the loader enforces (probed at and just past each bound), every presence rule
// of every row is enforced (a scene that keeps it is taken, one that breaks it refused naming the
// key), every name of an enumerated key is taken and no other, every default is accepted, `--set
// KEY=null` restores the default, and docs/scene.md, docs/contract.md and the fuzzer's dictionary
// agree with the table.

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
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

// "effects[air_drag]" -> "air_drag"; empty for any other block.
std::string effectOf(std::string_view block) {
  std::smatch match;
  const std::string text(block);
  return std::regex_match(text, match, std::regex(R"(effects\[([a-z_]+)\])")) ? match[1].str() : std::string();
}

// The object of `block` in the document, nullptr where the document has no such block. The test's
// own reading of the table's paths, apart from the reader's.
nlohmann::json* blockAt(nlohmann::json& document, std::string_view block) {
  if (block.empty()) return &document;
  if (const std::string effect = effectOf(block); !effect.empty()) {
    if (!document.contains("effects")) return nullptr;
    for (nlohmann::json& entry : document["effects"]) {
      if (entry.is_object() && entry.value("type", "") == effect) return &entry;
    }
    return nullptr;
  }
  if (block == "initial" || block == "initial[steady]") {
    if (!document.contains("initial")) return nullptr;
    nlohmann::json& initial = document["initial"];
    return initial.contains("steady") == (block == "initial[steady]") ? &initial : nullptr;
  }
  nlohmann::json* node = &document;
  std::istringstream segments{std::string(block)};
  for (std::string segment; std::getline(segments, segment, '.');) {
    if (!node->contains(segment)) return nullptr;
    node = &(*node)[segment];
  }
  return node;
}

const nlohmann::json* valueAt(nlohmann::json& document, const schema::Key& key) {
  nlohmann::json* block = blockAt(document, key.block());
  return block != nullptr && block->contains(key.name()) ? &(*block)[std::string(key.name())] : nullptr;
}

// Makes the block exist: an effect's entry (the only one), a steady start of the first kind, a nested object.
void enterBlock(nlohmann::json& document, std::string_view block) {
  if (blockAt(document, block) != nullptr) return;
  if (const std::string effect = effectOf(block); !effect.empty()) {
    document["effects"] = nlohmann::json::array({{{"type", effect}}});
  } else if (block == "initial[steady]") {
    document["initial"] = {{"steady", schema::kSteadyKindNames.front()}};
  } else if (block == "initial") {
    document["initial"] = nlohmann::json::object();
  } else {
    nlohmann::json* node = &document;
    std::istringstream segments{std::string(block)};
    for (std::string segment; std::getline(segments, segment, '.');) {
      if (!node->contains(segment)) (*node)[segment] = nlohmann::json::object();
      node = &(*node)[segment];
    }
  }
}

void put(nlohmann::json& document, const schema::Key& key, const nlohmann::json& value) {
  enterBlock(document, key.block());
  (*blockAt(document, key.block()))[std::string(key.name())] = value;
}

void erase(nlohmann::json& document, const schema::Key& key) {
  if (nlohmann::json* block = blockAt(document, key.block())) block->erase(std::string(key.name()));
}

// A value the key takes on its own: an effect's type its block's, a switch on, else the row's
// example, default or first name, an empty object.
nlohmann::json valueFor(const schema::Key& key) {
  if (key.name() == "type" && !effectOf(key.block()).empty()) return effectOf(key.block());
  if (key.type == schema::Type::Boolean) return true;
  if (!key.example.empty()) return nlohmann::json::parse(key.example);
  if (!key.defaultText.empty()) return nlohmann::json::parse(key.defaultText);
  if (!key.names.empty()) return std::string(key.names.front());
  return nlohmann::json::object();
}

bool holds(nlohmann::json& document, const schema::Condition& condition) {
  return std::any_of(condition.paths.begin(), condition.paths.end(), [&](const std::string& path) {
    const schema::Key& other = schema::key(path);
    const nlohmann::json* value = valueAt(document, other);
    if (condition.values.empty()) return value != nullptr;
    const nlohmann::json effective = value != nullptr            ? *value
                                     : other.defaultText.empty() ? nlohmann::json()
                                                                 : nlohmann::json::parse(other.defaultText);
    return std::any_of(condition.values.begin(), condition.values.end(),
                       [&](const std::string& wanted) { return effective == nlohmann::json::parse(wanted); });
  });
}

// Enters the key's block and meets its onlyWith and needs (but `except`), and theirs in turn.
void satisfy(nlohmann::json& document, const schema::Key& key, const schema::Condition* except = nullptr) {
  enterBlock(document, key.block());
  for (const auto* rules : {&key.onlyWith, &key.needs}) {
    for (const schema::Condition& condition : *rules) {
      if (&condition == except || holds(document, condition)) continue;
      const schema::Key& other = schema::key(condition.paths.front());
      satisfy(document, other);
      const nlohmann::json value =
          condition.values.empty() ? valueFor(other) : nlohmann::json::parse(condition.values.front());
      put(document, other, value);
    }
  }
}

// Makes `condition` fail: a named key given another of its names (a steady start's kind stays, as
// its block needs it), a switch off, any other key absent.
void breakCondition(nlohmann::json& document, const schema::Condition& condition) {
  for (const std::string& path : condition.paths) {
    const schema::Key& other = schema::key(path);
    if (other.type == schema::Type::Boolean)
      put(document, other, false);
    else if (other.names.empty())
      erase(document, other);
    for (const std::string_view name : other.names) {
      if (holds(document, condition)) put(document, other, std::string(name));
    }
  }
  ASSERT_FALSE(holds(document, condition)) << document.dump();
}

// Adds what the rows require where the document has their block: required keys (where their
// onlyWith holds) and the last of an object's needsOneOf.
void fill(nlohmann::json& document) {
  for (bool added = true; added;) {
    added = false;
    for (const schema::Key& key : schema::keys()) {
      if (blockAt(document, key.block()) == nullptr) continue;
      const bool allowed = std::all_of(key.onlyWith.begin(), key.onlyWith.end(),
                                       [&](const schema::Condition& c) { return holds(document, c); });
      if (key.required && allowed && valueAt(document, key) == nullptr) {
        put(document, key, valueFor(key));
        added = true;
      }
      const nlohmann::json* own = blockAt(document, key.path);
      const auto given = [own](const std::string& name) { return own->contains(name); };
      if (own != nullptr && !key.needsOneOf.empty() &&
          std::none_of(key.needsOneOf.begin(), key.needsOneOf.end(), given)) {
        put(document, schema::key(key.path + "." + key.needsOneOf.back()),
            valueFor(schema::key(key.path + "." + key.needsOneOf.back())));
        added = true;
      }
    }
  }
}

std::string refusalOf(const nlohmann::json& document) {
  try {
    parseScene(document, "scene.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return {};
}

// Where a bound probe meets a rule between two keys' numbers (the loader's, not the table's), the
// other key's value that leaves the probed bound the only one in play.
const std::map<std::string, std::vector<std::string>, std::less<>> kCrossKeyContext = {
    {"coin.I_X", {"coin.I_Z=2e-21"}},  // I_Z <= 2 I_X at the least I_X
    {"coin.I_Z", {"coin.I_X=1e15"}},   // and at the greatest I_Z
};

// The loader's refusal of the base scene with the key's presence rules met and `assignments`, or ""
// when it is accepted.
std::string refusal(const schema::Key& key, const std::vector<std::string>& assignments) {
  nlohmann::json document = baseScene();
  try {
    satisfy(document, key);
    if (const auto context = kCrossKeyContext.find(key.path); context != kCrossKeyContext.end()) {
      for (const std::string& assignment : context->second) applyOverride(document, assignment);
    }
    for (const std::string& assignment : assignments) applyOverride(document, assignment);
  } catch (const SceneError& e) {
    return e.what();
  }
  fill(document);
  return refusalOf(document);
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
                            : integer        ? bound->value - outward
                                             : std::nextafter(bound->value, -outward * INFINITY);
      const double outside = !bound->inclusive ? bound->value
                             : integer         ? bound->value + outward
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

// Each presence rule of each row, from the row: a scene that gives the key where its rules hold is
// taken; one where the rule is broken is refused with a message naming the key and the rule.
TEST(SceneSchema, EveryPresenceRuleIsEnforced) {
  const auto expectRefused = [](const nlohmann::json& document, std::string_view path, std::string_view rule) {
    const std::string refused = refusalOf(document);
    EXPECT_TRUE(refused.starts_with(fmt::format("scene.json: {}: ", messagePath(path))) &&
                refused.find(rule) != std::string::npos)
        << "expected " << path << ": " << rule << "; got " << refused << "\n  for " << document.dump();
  };
  int rules = 0;
  for (const schema::Key& key : schema::keys()) {
    const bool ruled =
        key.required || !key.onlyWith.empty() || !key.needs.empty() || !key.excludes.empty() || !key.needsOneOf.empty();
    if (!ruled) continue;
    SCOPED_TRACE(key.path);
    nlohmann::json accepted = baseScene();
    satisfy(accepted, key);
    put(accepted, key, valueFor(key));
    fill(accepted);
    EXPECT_EQ(refusalOf(accepted), "") << accepted.dump();
    if (key.required) {
      nlohmann::json missing = accepted;
      erase(missing, key);
      // An effect's type picks its block, so the entry without one is refused as a whole.
      const bool picksItsBlock = !effectOf(key.block()).empty() && key.name() == "type";
      expectRefused(missing, picksItsBlock ? key.block() : std::string_view(key.path), picksItsBlock ? "" : "required");
      ++rules;
    }
    for (const auto* list : {&key.onlyWith, &key.needs}) {
      for (const schema::Condition& condition : *list) {
        nlohmann::json broken = baseScene();
        satisfy(broken, key, &condition);
        breakCondition(broken, condition);
        put(broken, key, valueFor(key));
        fill(broken);
        expectRefused(broken, key.path, "only with");
        ++rules;
        // A misspelt name that the condition reads is the fault named, not the rule reading it.
        if (const schema::Key& other = schema::key(condition.paths.front()); !other.names.empty()) {
          put(broken, other, "no-such-name");
          expectRefused(broken, other.path, "must be");
        }
      }
    }
    for (const std::string& other : key.excludes) {
      nlohmann::json both = accepted;
      const schema::Key& excluded = schema::key(fmt::format("{}.{}", key.block(), other));
      put(both, excluded, valueFor(excluded));
      expectRefused(both, key.path, "not with");
      ++rules;
    }
    if (!key.needsOneOf.empty()) {
      nlohmann::json empty = baseScene();
      enterBlock(empty, key.path);
      expectRefused(empty, key.path, "needs one of");
      ++rules;
    }
  }
  EXPECT_GE(rules, 30);  // a rule lost from the table shows here
}

TEST(SceneSchema, EveryNameIsTakenAndNoOther) {
  for (const schema::Key& key : schema::keys()) {
    if (key.names.empty()) continue;
    SCOPED_TRACE(key.path);
    for (const std::string_view name : key.names) {
      // The name may still be refused beyond the table (a steady circle's f- root may not exist).
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

// The docs' key tables are printed from the schema, as the reader enforces it.
TEST(SceneSchema, TheDocsTablesAreTheSchemas) {
  EXPECT_NE(readSource("docs/scene.md").find(schema::toMarkdown()), std::string::npos)
      << "docs/scene.md's table is not the schema's: regenerate it with `coinroll schema --markdown`";
  EXPECT_NE(readSource("docs/contract.md").find(schema::toContractMarkdown()), std::string::npos)
      << "docs/contract.md's key table is not the schema's: regenerate it with `coinroll schema --contract`";
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

}  // namespace
}  // namespace coinroll::scene
