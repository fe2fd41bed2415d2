#pragma once
// `coinroll export`'s choices for the page a lecturer puts on a course site (docs/web.md "A page for
// a course"): its title and caption, which controls a student sees, and whether the researcher's
// details (the scene file, the run's log, the command) show or fold. They travel into the page as
// JSON in its placeholder `coinroll-page-options`, beside the scene's.

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace coinroll::cli {

struct PageOptions {
  std::optional<std::string> title;     // <title> and heading; default the scene's name
  std::optional<std::string> caption;   // a paragraph under the heading; default none
  std::optional<std::string> controls;  // comma-separated control keys or groups; default all
  std::string details = "folded";       // "folded" (one click away) or "shown"
};

// Characters (UTF-8 code points) a title and a caption may hold: a heading's line, a paragraph.
inline constexpr std::size_t kMaxTitleCharacters = 200;
inline constexpr std::size_t kMaxCaptionCharacters = 1000;

// Refuses (UsageError, naming the option and the fix) a title or caption that is empty, too long,
// not UTF-8 or holds control characters (a caption may hold line breaks), and a --details other than
// folded or shown. Needs nothing but the options, so it runs before anything is read.
void checkPageText(const PageOptions& options);

// The page options' JSON for the page `html` (the built page, whose `coinroll-controls` list names
// the controls it has, each a key of the scene schema), with `sceneName` the title when none is
// given (none: the page keeps its own). Refuses a control or group the page does not have, naming it
// and listing the valid ones; throws std::runtime_error for a page without a valid control list.
nlohmann::json pageOptionsJson(const PageOptions& options, std::string_view html, const std::string& pageName,
                               const std::optional<std::string>& sceneName);

}  // namespace coinroll::cli
