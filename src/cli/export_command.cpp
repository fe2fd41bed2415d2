// `coinroll export`: the web page (docs/web.md "The page") with a scene in it, as one HTML file.
// The page is built beside the program (tools/build_page.sh); the program only puts the scene in
// the page's placeholder, so the page that opens is the scene's, ready to play and to change.

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <optional>
#include <string>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"

namespace coinroll::cli {

namespace {

// The page's slot for the scene: the page starts from the default scene while it holds null.
constexpr std::string_view kScenePlaceholder = R"(<script type="application/json" id="coinroll-scene">null</script>)";

// Where the built page is: COINROLL_PAGE names it; else beside the program (build/web/, as
// tools/build_page.sh writes it) or where `cmake --install` puts it (share/coinroll/).
std::filesystem::path pageTemplate() {
  if (const char* named = std::getenv("COINROLL_PAGE"); named != nullptr && *named != '\0') return named;
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path candidates[] = {
      program.parent_path() / "web" / "coinroll.html",
      program.parent_path().parent_path() / "share" / "coinroll" / "coinroll.html"};
  for (const std::filesystem::path& candidate : candidates) {
    if (std::filesystem::is_regular_file(candidate, error)) return candidate;
  }
  throw std::runtime_error(fmt::format(
      "the web page is not built: looked for {} and {}; build it with tools/build_page.sh (it needs Debian's "
      "emscripten and npm, which tools/setup.sh installs), or name a built page with COINROLL_PAGE",
      candidates[0].string(), candidates[1].string()));
}

// JSON inside <script>: "</" would end the element early; "<\/" is the same JSON string.
std::string scriptSafe(const std::string& json) {
  std::string safe;
  for (std::size_t i = 0; i < json.size(); ++i) {
    safe += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') safe += '\\';
  }
  return safe;
}

// The digest of the scene a page at `path` holds (its placeholder filled by runExport), or none for a
// file that is no coinroll page with a scene in it.
std::optional<std::string> pageSceneDigest(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const std::string html = text.str();
  const std::string_view open = kScenePlaceholder.substr(0, kScenePlaceholder.find("null"));
  const std::size_t from = html.find(open);
  const std::size_t to = from == std::string::npos ? from : html.find("</script>", from);
  if (to == std::string::npos) return std::nullopt;
  const nlohmann::json scene =
      nlohmann::json::parse(html.substr(from + open.size(), to - from - open.size()), nullptr, false);
  if (scene.is_discarded() || scene.is_null()) return std::nullopt;
  return sceneDigestOf(scene);
}

}  // namespace

void runExport(const ExportOptions& options) {
  if (options.output) refuseEmptyOutputName("-o", *options.output, "page.html");
  const auto [document, sourceName] = loadSceneDocument(options.scene);
  // A scene the page would refuse is refused here, with the same message.
  const scene::SceneConfig scene = scene::parseScene(document, sourceName);
  const std::string output =
      options.output ? *options.output
                     : defaultOutputName(document.contains("name") && document.at("name") != "", scene.name,
                                         options.scene, ".html")
                           .string();
  refuseOverwritingInput("-o", output, inputsOf(options.scene));
  if (!options.output && !options.force) refuseTakingOverDefaultName(output, sceneDigestOf(document), pageSceneDigest);

  const std::filesystem::path page = pageTemplate();
  std::ifstream in(page, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the built page", page.string()));
  std::string html = text.str();
  const std::size_t slot = html.find(kScenePlaceholder);
  if (slot == std::string::npos) {
    throw std::runtime_error(fmt::format("{}: not a coinroll page (it has no scene placeholder); rebuild it with "
                                         "tools/build_page.sh", page.string()));
  }
  const std::string filled = std::string(kScenePlaceholder).replace(kScenePlaceholder.find("null"), 4,
                                                                    scriptSafe(document.dump()));
  html.replace(slot, kScenePlaceholder.size(), filled);
  writeTextOutput(output, "page", [&html](std::ostream& out) { out << html; });
  if (output != "-" && !options.quiet) {
    std::cerr << fmt::format("coinroll: wrote {} ({:.2f} MB: the scene, the WebAssembly core and three.js; opens from "
                             "file:// with no network)\n", scene::printable(output), html.size() / 1e6);
  }
}

}  // namespace coinroll::cli
