// `coinroll export`: the web page (docs/web.md "The page") with a scene in it, as one HTML file.
// The page is built beside the program (tools/build_page.sh); the program only puts the scene in
// the page's placeholder, so the page that opens is the scene's, ready to play and to change.

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "cli/page_options.h"
#include "io/destination.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"
#include "video/video_kinds.h"

namespace coinroll::cli {

namespace {

// The page's slot for the scene: the page starts from the default scene while it holds null.
constexpr std::string_view kScenePlaceholder = R"(<script type="application/json" id="coinroll-scene">null</script>)";
// The page's slot for its options (page_options.h): null, the page as built, for a developer.
constexpr std::string_view kOptionsPlaceholder =
    R"(<script type="application/json" id="coinroll-page-options">null</script>)";

// The built page is a few MB at most (the WebAssembly core, three.js and uPlot). What is read stops past
// this bound, so a name that leads to no page (a device that never ends, such as /dev/zero; a video; a
// 3 GB file under an exported page's name) is refused instead of filling memory. The bound leaves
// room for the page to grow and for an exported page's scene (a scene file is at most 16 MiB).
constexpr std::size_t kMaxPageBytes = 64 << 20;

// The page template and how messages name it: "COINROLL_PAGE=x.html" when the variable named it,
// so a user who set it long ago sees where the name came from.
struct PageTemplate {
  std::filesystem::path path;
  std::string name;
};

// Where the built page is: COINROLL_PAGE names it; else beside the program (build/web/, as
// tools/build_page.sh writes it) or where `cmake --install` puts it (share/coinroll/).
PageTemplate pageTemplate() {
  if (const char* named = std::getenv("COINROLL_PAGE"); named != nullptr && *named != '\0') {
    return {named, fmt::format("COINROLL_PAGE={}", scene::printable(named))};
  }
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path candidates[] = {
      program.parent_path() / "web" / "coinroll.html",
      program.parent_path().parent_path() / "share" / "coinroll" / "coinroll.html"};
  for (const std::filesystem::path& candidate : candidates) {
    if (std::filesystem::is_regular_file(candidate, error)) return {candidate, scene::printable(candidate.string())};
  }
  throw std::runtime_error(fmt::format(
      "the web page is not built: looked for {} and {}; cmake --build builds it where Debian's emscripten, node "
      "and web/node_modules are installed (tools/setup.sh installs them; tools/build_page.sh builds the page alone), "
      "or name a built page with COINROLL_PAGE",
      candidates[0].string(), candidates[1].string()));
}

// The text of the file at `path`, or none when it is longer than kMaxPageBytes. Read in blocks, so
// only what the file holds is allocated. Throws "NAME: cannot read the built page: WHY" for a file
// that cannot be opened or read, and "NAME: is a directory" for a directory (which opens, and
// then reads as nothing).
std::optional<std::string> readPage(const std::filesystem::path& path, const std::string& name) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw std::runtime_error(
        fmt::format("{}: is a directory; name the built page, coinroll.html (tools/build_page.sh "
                    "writes it to build/web/)",
                    name));
  }
  std::ifstream in(path, std::ios::binary);
  const auto refuse = [&name] {
    return std::runtime_error(fmt::format("{}: cannot read the built page: {}", name, std::strerror(errno)));
  };
  if (!in) throw refuse();
  std::string text;
  constexpr std::size_t kBlock = 1 << 20;
  while (in && text.size() <= kMaxPageBytes) {
    const std::size_t size = text.size();
    text.resize(size + kBlock);
    in.read(text.data() + size, static_cast<std::streamsize>(kBlock));
    text.resize(size + static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw refuse();
  if (text.size() > kMaxPageBytes) return std::nullopt;
  return text;
}

// JSON inside <script>: its text ends at the first "</script", and an "<!--" followed by "<script"
// makes the element swallow the page's next script (HTML's script-data escape states), leaving a
// dead page. A '<' appears in JSON only inside a string, where "\u003c" is the same character, so
// none is left to start either.
std::string scriptSafe(const std::string& json) {
  std::string safe;
  for (const char c : json) {
    if (c == '<')
      safe += "\\u003c";
    else
      safe += c;
  }
  return safe;
}

// The digest of the scene a page at `path` holds (its placeholder filled by runExport), or none for a
// file that is no coinroll page with a scene in it.
std::optional<std::string> pageSceneDigest(const std::filesystem::path& path) {
  std::optional<std::string> html;
  try {
    html = readPage(path, path.string());
  } catch (const std::runtime_error&) {
    return std::nullopt;  // unreadable: it cannot say which scene made it
  }
  if (!html) return std::nullopt;
  const std::string_view open = kScenePlaceholder.substr(0, kScenePlaceholder.find("null"));
  const std::size_t from = html->find(open);
  const std::size_t to = from == std::string::npos ? from : html->find("</script>", from);
  if (to == std::string::npos) return std::nullopt;
  const nlohmann::json scene =
      nlohmann::json::parse(html->substr(from + open.size(), to - from - open.size()), nullptr, false);
  if (scene.is_discarded() || scene.is_null()) return std::nullopt;
  return sceneDigestOf(scene);
}

}  // namespace

void runExport(const ExportOptions& options) {
  if (options.output) refuseEmptyOutputName("-o", *options.output, "page.html");
  // A page under another kind's name (page.mp4) opens as that kind, or not at all; a device, FIFO
  // or descriptor has no name to check.
  if (options.output && !video::namesExtension(*options.output, ".html") &&
      !video::namesExtension(*options.output, ".htm") && *options.output != "-" && !io::namesStream(*options.output)) {
    const std::string html = std::filesystem::path(*options.output).replace_extension(".html").string();
    throw UsageError(fmt::format("-o {}: export writes an HTML page; name it .html, e.g. -o {}",
                                 scene::printable(*options.output), scene::printable(html)));
  }
  checkPageText(options.page);
  const auto [document, sourceName] = loadSceneDocument(options.scene);
  // A scene the page would refuse is refused here, with the same message.
  const scene::SceneConfig scene = scene::parseScene(document, sourceName);
  const bool named = document.contains("name") && document.at("name") != "";
  const std::string output =
      options.output ? *options.output : defaultOutputName(named, scene.name, options.scene, ".html").string();
  // The template is read like the scene: an output over it would leave every later export without
  // a page.
  const PageTemplate page = pageTemplate();
  std::vector<std::filesystem::path> inputs = inputsOf(options.scene);
  inputs.push_back(page.path);
  refuseOverwritingInput("-o", output, inputs);
  if (!options.output && !options.force) refuseTakingOverDefaultName(output, sceneDigestOf(document), pageSceneDigest);

  std::optional<std::string> text = readPage(page.path, page.name);
  if (!text) {
    throw std::runtime_error(
        fmt::format("{}: more than {} bytes, far more than a built page: name the page "
                    "tools/build_page.sh builds (build/web/coinroll.html)",
                    page.name, kMaxPageBytes));
  }
  std::string html = std::move(*text);
  const std::size_t slot = html.find(kScenePlaceholder);
  if (slot == std::string::npos) {
    throw std::runtime_error(
        fmt::format("{}: not a coinroll page (it has no scene placeholder); rebuild it with "
                    "tools/build_page.sh",
                    page.name));
  }
  const std::size_t optionsSlot = html.find(kOptionsPlaceholder, slot);
  if (optionsSlot == std::string::npos) {
    throw std::runtime_error(
        fmt::format("{}: not a coinroll page of this version (it has no page-options "
                    "placeholder); rebuild it with tools/build_page.sh",
                    page.name));
  }
  // Every option is checked before the page is written: the controls against the page's own list.
  const nlohmann::json pageOptions =
      pageOptionsJson(options.page, html, page.name, named ? std::optional(scene.name) : std::nullopt);
  // The options' slot first: it lies after the scene's, whose filling would move it.
  html.replace(
      optionsSlot, kOptionsPlaceholder.size(),
      std::string(kOptionsPlaceholder).replace(kOptionsPlaceholder.find("null"), 4, scriptSafe(pageOptions.dump())));
  const std::string filled =
      std::string(kScenePlaceholder).replace(kScenePlaceholder.find("null"), 4, scriptSafe(document.dump()));
  html.replace(slot, kScenePlaceholder.size(), filled);
  writeTextOutput(output, "page", [&html](std::ostream& out) { out << html; });
  if (output != "-" && !options.quiet) {
    std::cerr << fmt::format(
        "coinroll: wrote {} ({:.2f} MB: the scene, the WebAssembly core and three.js; opens from "
        "file:// with no network)\n",
        scene::printable(output), html.size() / 1e6);
  }
}

}  // namespace coinroll::cli
