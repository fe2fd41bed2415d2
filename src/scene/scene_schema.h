#pragma once
// The scene file's keys as one table: path, type, unit, default, range, the presence rules that say
// where a key may or must be given, the names an enumerated key takes, and a line of documentation.
// The reader (scene/json_reader.h) takes from it the keys each object allows, their JSON types and
// presence rules, and the loader the ranges its numbers must lie in; `coinroll schema` prints it
// (JSON for the web page's controls and for scripts, Markdown for docs/scene.md and docs/contract.md),
// and tests probe every bound and presence rule of it. A new key is one row here plus its physics;
// the loader keeps only rules between numbers of several keys (inner_radius <= radius).

#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "physics/air_drag.h"
#include "physics/formulation.h"
#include "render/render_settings.h"

namespace coinroll::scene::schema {

// The file's names of each enumeration, in the order of the enum's values; each is checked against
// its enum's last value below, so a value added to an enum without its name fails to compile.
inline constexpr std::array<std::string_view, 3> kShapeNames = {"disk", "ring", "custom"};
inline constexpr std::array<std::string_view, 3> kSteadyKindNames = {"straight", "circle", "spin-in-place"};
inline constexpr std::array<std::string_view, 2> kFormulationNames = {"euler-angles", "quaternion"};
inline constexpr std::array<std::string_view, 2> kOnInvalidNames = {"stop", "warn"};
inline constexpr std::array<std::string_view, 3> kEffectTypeNames = {"air_drag", "rolling_resistance", "spin_friction"};
inline constexpr std::array<std::string_view, 2> kAirFlowNames = {"moffatt", "boundary_layer"};
inline constexpr std::array<std::string_view, 4> kAntialiasingNames = {"msaa", "fxaa", "ssaa", "auto"};
inline constexpr std::array<std::string_view, 2> kBackgroundNames = {"opaque", "transparent"};
inline constexpr std::array<std::string_view, 2> kThemeNames = {"classic", "paper"};
inline constexpr std::array<std::string_view, 3> kCameraModeNames = {"fixed", "orbit", "follow"};
inline constexpr std::array<std::string_view, 2> kPitchNames = {"video", "real"};
inline constexpr std::array<std::string_view, 2> kTimbreNames = {"clicks", "tone"};

template <class Enum, std::size_t N>
constexpr bool namesEveryValue(Enum last, const std::array<std::string_view, N>&) {
  return static_cast<std::size_t>(last) + 1 == N;
}
static_assert(namesEveryValue(physics::Formulation::Quaternion, kFormulationNames));
static_assert(namesEveryValue(physics::AirFlow::BoundaryLayer, kAirFlowNames));
static_assert(namesEveryValue(render::Antialiasing::Auto, kAntialiasingNames));
static_assert(namesEveryValue(render::Theme::Paper, kThemeNames));

enum class Type {
  Number,
  Integer,
  Boolean,
  Text,      // any string
  Name,      // one of `names`
  Point,     // [x, y, z]
  Object,    // a block of keys of its own
  List,      // effects
  Audio,     // true, false or an object of options
  ScaleBar,  // true, false or a length
};

struct Bound {
  double value;
  bool inclusive;
};

// A presence rule's condition on another key of the table ("flight", "coin.shape", and in the key's
// own block "effects[air_drag].model"): it holds where one of `paths` is given and, when `values`
// are listed (as JSON text: "true", "\"ring\""), where that key's value, or its default when it is
// absent, is one of them.
struct Condition {
  std::vector<std::string> paths;
  std::vector<std::string> values = {};
};

struct Key {
  std::string
      path;  // "coin.radius"; an effect's keys under "effects[<type>]"; a steady start's under "initial[steady]"
  Type type;
  std::string unit;         // as the docs write it: "m", "rad/s", "degrees"; empty when dimensionless
  std::string defaultText;  // the default as JSON text, taken from the structs; empty: required or absent
  bool required = false;    // given wherever its block is and its `onlyWith` hold
  // The range a number must lie in, when it is fixed (bounds that depend on other keys, such as
  // inner_radius <= radius, are the loader's and the doc's).
  std::optional<Bound> lower = std::nullopt, upper = std::nullopt;
  std::vector<std::string_view> names = {};  // Type::Name: the values allowed, in the enum's order
  // Presence beyond `required`, as MuJoCo's schema has required/requires/exclusive facets.
  std::vector<Condition> onlyWith = {};      // given only where these hold
  std::vector<Condition> needs = {};         // on (given, not false) only where these hold: "sliding": false is off
  std::vector<std::string> excludes = {};    // keys of its block never given beside it
  std::vector<std::string> needsOneOf = {};  // an object: at least one of these of its keys
  std::string presenceWhy = {};              // the reason a presence message gives in parentheses
  std::string example = {};                  // JSON text a message and the page suggest for a key without a default
  std::string why = {};                      // the reason a range message gives in parentheses
  bool unitInRule = true;    // false where the range message has always been bare ("must be in [1, 240]")
  bool powersOfTen = false;  // bounds written 1e-14 rather than 1e-14's %g form (the solver's tolerances)
  std::string doc = {};      // one line: what the key does, for docs/scene.md and the page's controls

  // The object the key sits in ("coin", "effects[air_drag]", "" for the top level) and its own name.
  std::string_view block() const;
  std::string_view name() const;
};

// Every key, each object's keys in the order its "allowed here" message lists them.
std::span<const Key> keys();

// The row for `path`; a path outside the table is a programming error (std::logic_error).
const Key& key(std::string_view path);

// The names `block` allows, for JsonReader and its "unknown key; allowed here: ..." message.
std::span<const std::string_view> keysIn(std::string_view block);

// "must be in (0, 10000] m/s^2, got 12345": the range rule of `key` for `value`, empty when the
// value lies in the range.
std::string rangeViolation(const Key& key, double value);

// "\"a\", \"b\" or \"c\"".
std::string quotedAlternatives(std::span<const std::string_view> names);

// "number", "boolean or object": the type as docs/scene.md and the page name it.
std::string_view typeName(Type type);

// A condition as messages and docs write it: `shape: "ring"`, `thickness`, `spin_rate or
// precession_rate`; keys of `block` by their name, others by their path.
std::string conditionText(const Condition& condition, std::string_view block);

// The key's presence rules in words, for the docs' tables: "required", "only with `flight: true`".
std::string presenceText(const Key& key);

// The table as JSON, for `coinroll schema` and the web page's controls.
nlohmann::json toJson();

// The table as docs/scene.md's Markdown table.
std::string toMarkdown();

// docs/contract.md's table: every key with its type, unit and presence rules, what scripts may rely
// on staying as it is.
std::string toContractMarkdown();

}  // namespace coinroll::scene::schema
