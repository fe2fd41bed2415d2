#include "scene/json_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "scene/scene_loader.h"

namespace coinroll::scene {

std::string describeJson(const nlohmann::json& value) {
  // A --set value is any argv text, so a string here need not be UTF-8 (found by the fuzzer):
  // describe it with replacement characters rather than throw from inside an error message.
  const auto text = [&] { return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); };
  switch (value.type()) {
    case nlohmann::json::value_t::string: return "string " + text();
    case nlohmann::json::value_t::boolean: return "boolean " + text();
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    default: return text();
  }
}

namespace {

// A byte that a terminal takes for a command rather than a character (DEL included).
bool isControl(char c) {
  const auto byte = static_cast<unsigned char>(c);
  return byte < 0x20 || byte == 0x7f;
}

}  // namespace

std::string printable(std::string_view text) {
  std::string shown;
  for (const char c : text) {
    if (c == '\n')
      shown += "\\n";
    else if (isControl(c) && c != '\t')
      shown += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    else
      shown += c;
  }
  return shown;
}

std::string printableKey(std::string_view key) {
  if (std::none_of(key.begin(), key.end(), isControl)) return std::string(key);
  return nlohmann::json(std::string(key)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

JsonReader::JsonReader(const nlohmann::json& object, std::string path, std::string_view source, std::string_view block,
                       const nlohmann::json* top)
    : object_(object), top_(top != nullptr ? *top : object), path_(std::move(path)), source_(source), block_(block) {
  const std::span<const std::string_view> allowedKeys = schema::keysIn(block);
  if (!object_.is_object()) {
    throw SceneError(fmt::format("{}: {}: must be an object, got {}", source_, path_.empty() ? "(top level)" : path_,
                                 describeJson(object_)),
                     SceneError::Kind::WrongType);
  }
  for (const auto& [key, value] : object_.items()) {
    bool known = false;
    for (std::string_view allowed : allowedKeys) known = known || allowed == key;
    if (!known) {
      throw SceneError(fmt::format("{}: unknown key; allowed here: {}", where(key), fmt::join(allowedKeys, ", ")),
                       SceneError::Kind::UnknownKey);
    }
  }
  checkTypes();
  checkPresence();
}

JsonReader JsonReader::nested(const nlohmann::json& object, std::string path, std::string_view block) const {
  return JsonReader(object, std::move(path), source_, block, &top_);
}

namespace {

constexpr long long kIntegerLimit = 1'000'000'000;

}  // namespace

void JsonReader::checkTypes() const {
  using schema::Type;
  for (const auto& [key, value] : object_.items()) {
    const std::string got = describeJson(value);
    switch (spec(key).type) {
      case Type::Number:
        if (!value.is_number()) fail(key, "must be a number, got " + got);
        if (const double number = value.get<double>(); !std::isfinite(number)) {
          fail(key, fmt::format("must be a finite number, got {}", number));
        }
        break;
      case Type::Integer:
        if (value.is_number_float()) {
          const double d = value.get<double>();
          if (!(std::isfinite(d) && d == std::floor(d) && std::abs(d) < kIntegerLimit)) {
            fail(key, "must be an integer, got " + got);
          }
        } else if (!value.is_number_integer()) {
          fail(key, "must be an integer, got " + got);
        } else if (value.is_number_unsigned()
                       ? value.get<unsigned long long>() > kIntegerLimit
                       : value.get<long long>() < -kIntegerLimit || value.get<long long>() > kIntegerLimit) {
          // JSON integers from 2^63 up arrive unsigned; read as signed they would wrap to negatives.
          fail(key, fmt::format("out of range [{}, {}], got {}", -kIntegerLimit, kIntegerLimit, got));
        }
        break;
      case Type::Boolean:
        if (!value.is_boolean()) fail(key, "must be true or false, got " + got, SceneError::Kind::WrongType);
        break;
      case Type::Text:
      case Type::Name:
        if (!value.is_string()) fail(key, "must be a string, got " + got, SceneError::Kind::WrongType);
        break;
      case Type::Object:
        if (!value.is_object()) fail(key, "must be an object, got " + got, SceneError::Kind::WrongType);
        break;
      case Type::Point:
      case Type::List:
      case Type::Audio:
      case Type::ScaleBar: break;
    }
  }
}

const nlohmann::json* JsonReader::find(std::string_view path) const {
  const schema::Key& row = schema::key(path);
  if (row.block() == block_) return child(row.name());
  // A key of another block, by its dotted path from the top (no condition names a list's entry).
  const nlohmann::json* node = &top_;
  for (std::size_t start = 0; start <= path.size();) {
    const std::size_t dot = std::min(path.find('.', start), path.size());
    if (!node->is_object()) return nullptr;
    const auto it = node->find(path.substr(start, dot - start));
    if (it == node->end()) return nullptr;
    node = &*it;
    start = dot + 1;
  }
  return node;
}

bool JsonReader::holds(const schema::Condition& condition) const {
  for (const std::string& path : condition.paths) {
    const nlohmann::json* value = find(path);
    if (condition.values.empty()) {
      if (value != nullptr) return true;
      continue;
    }
    const schema::Key& other = schema::key(path);
    // A misspelt name is the fault to name, not the rule that reads it ("rign" and an inner_radius).
    if (value != nullptr && value->is_string() && !other.names.empty() &&
        std::find(other.names.begin(), other.names.end(), value->get<std::string>()) == other.names.end()) {
      const std::string rule =
          fmt::format("must be {}, got \"{}\"", schema::quotedAlternatives(other.names), value->get<std::string>());
      if (other.block() == block_) fail(other.name(), rule);
      throw SceneError(fmt::format("{}: {}: {}", source_, path, rule));
    }
    // A value rule holds for the default too: an air_drag entry without a model is Moffatt's.
    const std::string& fallback = other.defaultText;
    if (value == nullptr && fallback.empty()) continue;
    const nlohmann::json effective = value != nullptr ? *value : nlohmann::json::parse(fallback);
    for (const std::string& wanted : condition.values) {
      if (effective == nlohmann::json::parse(wanted)) return true;
    }
  }
  return false;
}

// The presence messages share one shape, "<key>: <rule> (<why>); <fix>", so that each names the
// key, what it needs, and the edit that makes the scene one the program takes.
void JsonReader::checkPresence() const {
  const auto conditions = [this](const std::vector<schema::Condition>& list, bool withExamples) {
    std::vector<std::string> texts;
    for (const schema::Condition& c : list) {
      std::string text = schema::conditionText(c, block_);
      const std::string& example = schema::key(c.paths.front()).example;
      if (withExamples && c.values.empty() && c.paths.size() == 1 && !example.empty()) text += ", e.g. " + example;
      texts.push_back(std::move(text));
    }
    return fmt::format("{}", fmt::join(texts, " and "));
  };
  const auto allHold = [this](const std::vector<schema::Condition>& list) {
    return std::all_of(list.begin(), list.end(), [this](const schema::Condition& c) { return holds(c); });
  };
  for (const std::string_view name : schema::keysIn(block_)) {
    const schema::Key& row = spec(name);
    const auto why = [&row] {
      const std::string unit = row.unit.empty() ? "" : " in " + row.unit;
      return row.presenceWhy.empty() ? fmt::format(" (a {}{})", schema::typeName(row.type), unit)
                                     : fmt::format(" ({})", row.presenceWhy);
    };
    const nlohmann::json* value = child(name);
    if (value != nullptr) {
      for (const std::string& other : row.excludes) {
        if (has(other)) fail(name, fmt::format("not with {}{}; remove one of them", other, why()));
      }
      if (!allHold(row.onlyWith)) {
        fail(name, fmt::format("only with {}{}; remove {} or give {}", conditions(row.onlyWith, false), why(), name,
                               conditions(row.onlyWith, true)));
      }
      const bool on = !(value->is_boolean() && !value->get<bool>());
      if (on && !allHold(row.needs)) {
        fail(name, fmt::format("{} only with {}{}; remove {} or give {}", value->dump(), conditions(row.needs, false),
                               why(), name, conditions(row.needs, true)));
      }
    } else if (row.required && allHold(row.onlyWith)) {
      const std::string with = row.onlyWith.empty() ? "" : " with " + conditions(row.onlyWith, false);
      const std::string example = row.example.empty() ? "" : fmt::format(", e.g. \"{}\": {}", name, row.example);
      fail(name, fmt::format("required{}{}; add it{}", with, why(), example));
    }
  }
  for (const schema::Key& own : schema::keys()) {
    if (own.path != block_ || own.needsOneOf.empty()) continue;
    if (std::none_of(own.needsOneOf.begin(), own.needsOneOf.end(), [this](const auto& k) { return has(k); })) {
      const std::string_view last = own.needsOneOf.back();
      const std::vector<std::string_view> others(own.needsOneOf.begin(), own.needsOneOf.end() - 1);
      throw SceneError(fmt::format("{}: {}: needs one of {} or {} ({}); add one or remove {}", source_, path_,
                                   fmt::join(others, ", "), last, own.presenceWhy, own.name()));
    }
  }
}

bool JsonReader::has(std::string_view key) const { return object_.contains(key); }

const schema::Key& JsonReader::spec(std::string_view key) const {
  return schema::key(block_.empty() ? std::string(key) : fmt::format("{}.{}", block_, key));
}

double JsonReader::bounded(std::string_view key, double value) const {
  if (const std::string rule = schema::rangeViolation(spec(key), value); !rule.empty()) fail(key, rule);
  return value;
}

std::string JsonReader::where(std::string_view key) const {
  return path_.empty() ? fmt::format("{}: {}", source_, printableKey(key))
                       : fmt::format("{}: {}.{}", source_, path_, printableKey(key));
}

void JsonReader::fail(std::string_view key, const std::string& rule, SceneError::Kind kind) const {
  throw SceneError(fmt::format("{}: {}", where(key), rule), kind);
}

const nlohmann::json* JsonReader::given(std::string_view key, std::initializer_list<schema::Type> types) const {
  const schema::Type type = spec(key).type;
  if (std::find(types.begin(), types.end(), type) == types.end()) {
    throw std::logic_error(
        fmt::format("scene reader: {} is a {}, not read this way", spec(key).path, schema::typeName(type)));
  }
  return child(key);
}

std::optional<double> JsonReader::optionalNumber(std::string_view key) const {
  // A scale bar is a number only where the loader found one.
  const nlohmann::json* value = given(key, {schema::Type::Number, schema::Type::ScaleBar});
  if (value == nullptr) return std::nullopt;
  return value->get<double>();
}

double JsonReader::requiredNumber(std::string_view key) const {
  const std::optional<double> value = optionalNumber(key);
  if (!value)
    throw std::logic_error(
        fmt::format("scene reader: {} is read as required, and its row does not say so", spec(key).path));
  return *value;
}

int JsonReader::integer(std::string_view key, int fallback) const {
  const nlohmann::json* value = given(key, {schema::Type::Integer});
  if (value == nullptr) return fallback;
  return value->is_number_float() ? static_cast<int>(value->get<double>()) : static_cast<int>(value->get<long long>());
}

bool JsonReader::boolean(std::string_view key, bool fallback) const {
  // A scale bar is a boolean only where the loader found one.
  const nlohmann::json* value = given(key, {schema::Type::Boolean, schema::Type::ScaleBar});
  return value == nullptr ? fallback : value->get<bool>();
}

std::optional<std::string> JsonReader::optionalString(std::string_view key) const {
  const nlohmann::json* value = given(key, {schema::Type::Text, schema::Type::Name});
  if (value == nullptr) return std::nullopt;
  return value->get<std::string>();
}

const nlohmann::json* JsonReader::child(std::string_view key) const {
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

}  // namespace coinroll::scene
