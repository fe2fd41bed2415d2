#include "scene/scene_override.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <string>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene_error.h"
#include "scene/scene_schema.h"

namespace coinroll::scene {

namespace {

// "effects[air_drag].length" -> "effects.length": a schema path without the variant of its block,
// as a --set path reads once its list indices are dropped.
std::string withoutVariants(std::string_view path) {
  std::string plain;
  bool inVariant = false;
  for (const char c : path) {
    if (c == '[')
      inVariant = true;
    else if (c == ']')
      inVariant = false;
    else if (!inVariant)
      plain += c;
  }
  return plain;
}

// The names the scene format allows in `block` (a dotted path without list indices): every
// variant's, for a block that has several ("initial" and "initial[steady]"; each effect type's).
std::vector<std::string_view> namesIn(std::string_view block) {
  std::vector<std::string_view> names;
  for (const schema::Key& key : schema::keys()) {
    if (withoutVariants(key.block()) == block && std::find(names.begin(), names.end(), key.name()) == names.end())
      names.push_back(key.name());
  }
  return names;
}

// A removal (KEY=null) whose key the scene does not hold changes nothing, so the loader never sees
// the key to refuse it: a misspelt --set nosuchkey=null would pass in silence while nosuchkey=1 is
// refused. Each name along the path must be one the scene format has, as if it were being set.
void refuseUnknownRemoval(std::string_view assignment, std::string_view path) {
  std::string block, walked;
  while (!path.empty()) {
    const std::string_view key = path.substr(0, path.find('.'));
    path = path.size() > key.size() ? path.substr(key.size() + 1) : std::string_view();
    if (!walked.empty()) walked += '.';
    walked += printableKey(key);
    if (std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;  // a list entry
    const std::vector<std::string_view> allowed = namesIn(block);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      throw SceneError(fmt::format("--set {}: {}: unknown key; allowed here: {}", printable(assignment), walked,
                                   fmt::join(allowed, ", ")),
                       SceneError::Kind::UnknownKey);
    }
    if (!block.empty()) block += '.';
    block += key;
  }
}

}  // namespace

void applyOverride(nlohmann::json& document, std::string_view assignment) {
  const auto equals = assignment.find('=');
  const std::string_view path = assignment.substr(0, equals);
  if (equals == std::string_view::npos || path.empty() || path.front() == '.' || path.back() == '.' ||
      path.find("..") != std::string_view::npos) {
    throw SceneError(fmt::format("--set {}: expected KEY.PATH=VALUE, e.g. --set initial.theta=12", assignment),
                     SceneError::Kind::UnknownKey);
  }
  const std::string text(assignment.substr(equals + 1));
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;
  try {
    // A scene is JSON, so UTF-8: refused here, the bytes would fail later wherever the document
    // is written out again (a sweep's identity) with a library's message.
    (void)value.dump();
  } catch (const nlohmann::json::type_error&) {
    throw SceneError(fmt::format("--set {}: the value is not UTF-8 text; scene values are UTF-8, as in a JSON file",
                                 printableKey(path)));
  }

  // Objects are walked by key, lists (effects) by index: effects.0.length is the first effect's
  // length. A missing key is created as an object (except to remove what is not there); a list is never created or
  // lengthened, since a half-given entry (an effect without its type) would only fail later with a vaguer message.
  nlohmann::json* node = &document;
  std::string_view rest = path;
  std::string walked;  // the path so far, for messages
  while (true) {
    const auto dot = rest.find('.');
    const std::string key(rest.substr(0, dot));
    const bool isIndex =
        !key.empty() && std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (node->is_array()) {
      std::size_t index = 0;
      const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), index);
      if (!isIndex || error != std::errc() || end != key.data() + key.size() || index >= node->size()) {
        throw SceneError(
            fmt::format("--set {}: {} is a list of {} entries, numbered 0 to {}; '{}' is none of them (--set "
                        "changes an entry, it cannot add one: add it in the scene file)",
                        assignment, walked, node->size(), static_cast<long>(node->size()) - 1, key),
            SceneError::Kind::UnknownKey);
      }
      if (dot == std::string_view::npos) {
        if (value.is_null())
          node->erase(index);
        else
          (*node)[index] = std::move(value);
        return;
      }
      node = &(*node)[index];
    } else if (node->is_object()) {
      if (isIndex && node != &document && node->empty()) {
        throw SceneError(
            fmt::format("--set {}: the scene has no {} list; --set changes an entry of a list but cannot make "
                        "one: write {} in the scene file",
                        assignment, walked, walked),
            SceneError::Kind::UnknownKey);
      }
      const bool removal = value.is_null();
      if (removal && !node->contains(key)) {
        // Nothing to remove, which is the default asked for, if the key is one the scene could hold.
        refuseUnknownRemoval(assignment, path);
        return;
      }
      if (dot == std::string_view::npos) {
        if (removal)
          node->erase(key);
        else
          (*node)[key] = std::move(value);
        return;
      }
      node = &(*node)[key];
      if (node->is_null()) *node = nlohmann::json::object();
    } else {
      throw SceneError(
          fmt::format("--set {}: {} is {}, which has no field '{}'", assignment, walked, describeJson(*node), key),
          SceneError::Kind::UnknownKey);
    }
    walked += (walked.empty() ? "" : ".") + key;
    rest = rest.substr(dot + 1);
  }
}

void applyOverrides(nlohmann::json& document, std::span<const std::string> overrides,
                    const std::optional<nlohmann::json>& initial) {
  if (initial && document.is_object()) document["initial"] = *initial;
  for (const std::string& assignment : overrides) applyOverride(document, assignment);
}

}  // namespace coinroll::scene
