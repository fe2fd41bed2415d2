#pragma once
// Typed, path-aware access to one JSON object of a scene: every read names "<source>: <path>.<key>"
// in its error, and the object is held to its block of the scene schema on construction (unknown
// keys, JSON types, presence rules), so a typo never passes silently and the loader reads only
// what the schema's rows let through.

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_error.h"
#include "scene/scene_schema.h"

namespace coinroll::scene {

class JsonReader {
 public:
  // Throws SceneError, in this order, if `object` is not a JSON object, has a key outside the
  // schema's `block` ("coin", "effects[air_drag]"; "" for the top level), holds a key whose JSON
  // type is not its row's (numbers, integers, booleans, strings, names, objects; the composite
  // types are checked where they are read), or breaks a presence rule of the block's rows, each
  // message naming the key and the fix. `path` is the object's name in messages ("effects[0]").
  // `top` is the scene document, where conditions on keys of other blocks are looked up (nullptr:
  // `object` is the document).
  JsonReader(const nlohmann::json& object, std::string path, std::string_view source, std::string_view block,
             const nlohmann::json* top = nullptr);

  // A reader of `object`, a block inside this reader's document.
  JsonReader nested(const nlohmann::json& object, std::string path, std::string_view block) const;

  bool has(std::string_view key) const;

  // Typed reads. The JSON type is the key's row's, checked on construction; a read of a key whose row
  // has another type is a programming error (std::logic_error).
  std::optional<double> optionalNumber(std::string_view key) const;
  double number(std::string_view key, double fallback) const { return optionalNumber(key).value_or(fallback); }
  double requiredNumber(std::string_view key) const;  // a key its row marks required
  int integer(std::string_view key, int fallback) const;
  bool boolean(std::string_view key, bool fallback) const;
  std::optional<std::string> optionalString(std::string_view key) const;
  const nlohmann::json* child(std::string_view key) const;  // nullptr when absent

  // The schema's row for `key` of this object.
  const schema::Key& spec(std::string_view key) const;
  // `value`, read at `key`, when it lies in the schema's range for the key; else SceneError.
  double bounded(std::string_view key, double value) const;

  // "<source>: <path>.<key>" for messages.
  std::string where(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& rule,
                         SceneError::Kind kind = SceneError::Kind::BadValue) const;

 private:
  void checkTypes() const;
  void checkPresence() const;
  // The value of a key of the table (its path) in this document, nullptr where absent.
  const nlohmann::json* find(std::string_view path) const;
  bool holds(const schema::Condition& condition) const;
  const nlohmann::json* given(std::string_view key, std::initializer_list<schema::Type> types) const;

  const nlohmann::json& object_;
  const nlohmann::json& top_;
  std::string path_;
  std::string source_;
  std::string block_;
};

// "string \"long\"", "number -1", "object", ... for "got ..." in messages.
std::string describeJson(const nlohmann::json& value);

// Text that users gave (file names, --set values, scene text) as a message quotes it: a control
// character among it would act on the terminal instead of showing, and a line break would split
// the one-line message a script reads, so each is shown as \xNN (a line break as \n), tabs kept.
std::string printable(std::string_view text);

// A key from a scene file as a message shows it: as it is when it is printable, otherwise as a
// JSON string with its control characters escaped ("ab\u0000c"), so a key cannot cut a message
// short at a NUL or send escape sequences to the user's terminal.
std::string printableKey(std::string_view key);

}  // namespace coinroll::scene
