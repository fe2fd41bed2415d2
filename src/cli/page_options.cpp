// `coinroll export`'s page options (page_options.h): checked before anything is written, the
// controls against the list the page itself declares, each of whose keys is a scene schema row.

#include "cli/page_options.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/exit_codes.h"
#include "cli/nearest_name.h"
#include "scene/json_reader.h"
#include "scene/scene_schema.h"

namespace coinroll::cli {

namespace {

// The page's list of its controls, in its groups (web/src/page.html), which web/src/controls.js
// builds the controls from.
constexpr std::string_view kControlsOpen = R"(<script type="application/json" id="coinroll-controls">)";

// The preset that shows every control, beside the page's groups.
constexpr std::string_view kAllControls = "all";

// The number of code points of valid UTF-8 `text`, or none where it is not UTF-8.
std::optional<std::size_t> codePoints(std::string_view text) {
  try {
    (void)nlohmann::json(std::string(text)).dump();  // strict: throws on a byte that is not UTF-8
  } catch (const nlohmann::json::type_error&) {
    return std::nullopt;
  }
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

void checkText(std::string_view option, std::string_view text, std::size_t maxCharacters, bool lineBreaks,
               std::string_view fix) {
  const std::optional<std::size_t> length = codePoints(text);
  if (!length) throw UsageError(fmt::format("{}: not UTF-8 text; {}", option, fix));
  if (*length == 0) throw UsageError(fmt::format("{}: empty; {}", option, fix));
  if (*length > maxCharacters) {
    throw UsageError(fmt::format("{}: {} characters, more than {}; {}", option, *length, maxCharacters, fix));
  }
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 || byte == 0x7F) && !(lineBreaks && c == '\n')) {
      throw UsageError(fmt::format("{} {}: holds a control character{}; {}", option, scene::printable(text),
                                   lineBreaks ? " (only line breaks may be)" : "", fix));
    }
  }
}

struct ControlGroup {
  std::string name;               // "initial", as --controls takes it
  std::vector<std::string> keys;  // "initial.theta", "effects[air_drag]"
};

// Whether a control's key is a row of the scene schema; an effect's box stands for its entry's type.
bool isSchemaKey(const std::string& key) {
  const std::string path = key.starts_with("effects[") && key.ends_with("]") ? key + ".type" : key;
  return std::ranges::any_of(scene::schema::keys(), [&path](const scene::schema::Key& k) { return k.path == path; });
}

// The page's control list: [{"group": "coin", "title": "Coin", "keys": ["coin.shape", ...]}, ...].
std::vector<ControlGroup> pageControls(std::string_view html, const std::string& pageName) {
  const auto refuse = [&pageName](const std::string& why) {
    return std::runtime_error(
        fmt::format("{}: not a coinroll page of this version ({}); rebuild it with "
                    "tools/build_page.sh",
                    pageName, why));
  };
  const std::size_t from = html.find(kControlsOpen);
  const std::size_t to = from == std::string_view::npos ? from : html.find("</script>", from);
  if (to == std::string_view::npos) throw refuse("it has no list of its controls");
  const nlohmann::json list =
      nlohmann::json::parse(html.substr(from + kControlsOpen.size(), to - from - kControlsOpen.size()), nullptr, false);
  if (!list.is_array()) throw refuse("its list of controls is not a JSON array");
  std::vector<ControlGroup> groups;
  for (const nlohmann::json& group : list) {
    if (!group.is_object() || !group.contains("group") || !group["group"].is_string() || !group.contains("keys") ||
        !group["keys"].is_array()) {
      throw refuse("a group of its controls has no name or keys");
    }
    ControlGroup read{group["group"].get<std::string>(), {}};
    for (const nlohmann::json& key : group["keys"]) {
      if (!key.is_string() || !isSchemaKey(key.get<std::string>())) {
        throw refuse(fmt::format("its control {} is no key of coinroll schema", scene::printable(key.dump())));
      }
      read.keys.push_back(key.get<std::string>());
    }
    groups.push_back(std::move(read));
  }
  return groups;
}

// The controls --controls names, in the page's order; none for every control.
std::optional<std::vector<std::string>> chosenControls(const std::string& list,
                                                       const std::vector<ControlGroup>& groups) {
  std::vector<std::string> every, names{std::string(kAllControls)};
  for (const ControlGroup& group : groups) {
    every.insert(every.end(), group.keys.begin(), group.keys.end());
    names.push_back(group.name);
  }
  const auto valid = [&] {
    return fmt::format("give control keys as the page's tooltips name them ({}) or a group ({}), separated by commas",
                       fmt::join(every, ", "), fmt::join(names, ", "));
  };
  const auto suggestion = [&](const std::string& item) {
    std::vector<std::string> candidates = every;
    candidates.insert(candidates.end(), names.begin(), names.end());
    const std::optional<std::string> nearest = nearestName(item, candidates);
    return nearest ? fmt::format("did you mean {}? ", *nearest) : std::string();
  };
  if (list.empty()) throw UsageError(fmt::format("--controls: empty; {}, or leave --controls out for all", valid()));
  std::vector<std::string> chosen;
  bool all = false;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    std::string item = list.substr(start, comma - start);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (item.empty()) {
      throw UsageError(fmt::format("--controls {}: an empty name between commas; {}", scene::printable(list), valid()));
    }
    const auto group = std::ranges::find(groups, item, &ControlGroup::name);
    if (item == kAllControls)
      all = true;
    else if (group != groups.end())
      chosen.insert(chosen.end(), group->keys.begin(), group->keys.end());
    else if (std::ranges::find(every, item) != every.end())
      chosen.push_back(item);
    else
      throw UsageError(fmt::format("--controls {}: no such control on the page; {}{}", scene::printable(item),
                                   suggestion(item), valid()));
    if (comma == list.size()) break;
    start = comma + 1;
  }
  if (all) return std::nullopt;
  std::vector<std::string> ordered;  // the page's order, each once
  std::ranges::copy_if(every, std::back_inserter(ordered),
                       [&chosen](const std::string& key) { return std::ranges::find(chosen, key) != chosen.end(); });
  return ordered;
}

}  // namespace

void checkPageText(const PageOptions& options) {
  if (options.title) {
    checkText("--title", *options.title, kMaxTitleCharacters, false,
              "give the page's heading as one line of text, or leave --title out for the scene's name");
  }
  if (options.caption) {
    checkText("--caption", *options.caption, kMaxCaptionCharacters, true,
              "give a short paragraph under the heading, or leave --caption out for none; longer text belongs on the "
              "course page around the page");
  }
  if (options.details != "folded" && options.details != "shown") {
    throw UsageError(
        fmt::format("--details {}: must be folded (one click away) or shown", scene::printable(options.details)));
  }
}

nlohmann::json pageOptionsJson(const PageOptions& options, std::string_view html, const std::string& pageName,
                               const std::optional<std::string>& sceneName) {
  const std::vector<ControlGroup> groups = pageControls(html, pageName);
  nlohmann::json json = nlohmann::json::object();
  json["title"] = options.title ? nlohmann::json(*options.title)
                  : sceneName   ? nlohmann::json(*sceneName)
                                : nlohmann::json(nullptr);
  json["caption"] = options.caption ? nlohmann::json(*options.caption) : nlohmann::json(nullptr);
  const std::optional<std::vector<std::string>> controls =
      options.controls ? chosenControls(*options.controls, groups) : std::nullopt;
  json["controls"] = controls ? nlohmann::json(*controls) : nlohmann::json(nullptr);
  json["details"] = options.details;
  return json;
}

}  // namespace coinroll::cli
