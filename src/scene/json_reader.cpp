#include "scene/json_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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
    if (c == '\n') shown += "\\n";
    else if (isControl(c) && c != '\t') shown += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    else shown += c;
  }
  return shown;
}

std::string printableKey(std::string_view key) {
  if (std::none_of(key.begin(), key.end(), isControl)) return std::string(key);
  return nlohmann::json(std::string(key)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

JsonReader::JsonReader(const nlohmann::json& object, std::string path, std::string_view source, std::string_view block)
    : object_(object), path_(std::move(path)), source_(source), block_(block) {
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

std::optional<double> JsonReader::optionalNumber(std::string_view key) const {
  const nlohmann::json* value = child(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_number()) fail(key, "must be a number, got " + describeJson(*value));
  const double number = value->get<double>();
  if (!std::isfinite(number)) fail(key, fmt::format("must be a finite number, got {}", number));
  return number;
}

double JsonReader::requiredNumber(std::string_view key) const {
  const std::optional<double> value = optionalNumber(key);
  if (!value) fail(key, "required (a number)");
  return *value;
}

int JsonReader::integer(std::string_view key, int fallback) const {
  const nlohmann::json* value = child(key);
  if (value == nullptr) return fallback;
  if (!value->is_number_integer()) {
    if (value->is_number_float()) {
      const double d = value->get<double>();
      if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 1e9) return static_cast<int>(d);
    }
    fail(key, "must be an integer, got " + describeJson(*value));
  }
  constexpr long long kLimit = 1'000'000'000;
  // JSON integers from 2^63 up arrive unsigned; read as signed they would wrap to negatives.
  if (value->is_number_unsigned() && value->get<unsigned long long>() > static_cast<unsigned long long>(kLimit)) {
    fail(key, fmt::format("out of range [{}, {}], got {}", -kLimit, kLimit, value->get<unsigned long long>()));
  }
  const auto number = value->get<long long>();
  if (number < -kLimit || number > kLimit)
    fail(key, fmt::format("out of range [{}, {}], got {}", -kLimit, kLimit, number));
  return static_cast<int>(number);
}

bool JsonReader::boolean(std::string_view key, bool fallback) const {
  const nlohmann::json* value = child(key);
  if (value == nullptr) return fallback;
  if (!value->is_boolean())
    fail(key, "must be true or false, got " + describeJson(*value), SceneError::Kind::WrongType);
  return value->get<bool>();
}

std::optional<std::string> JsonReader::optionalString(std::string_view key) const {
  const nlohmann::json* value = child(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_string()) fail(key, "must be a string, got " + describeJson(*value), SceneError::Kind::WrongType);
  return value->get<std::string>();
}

const nlohmann::json* JsonReader::child(std::string_view key) const {
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

}  // namespace coinroll::scene
