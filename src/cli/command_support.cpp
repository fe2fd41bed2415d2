#include "cli/command_support.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <optional>

#include "io/fnv1a.h"
#include "io/output_file.h"
#include "pipeline/inputs.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"
#include "scene/scene_text.h"
#include "video/make_sink.h"

namespace coinroll::cli {

namespace {

// `-` as the scene is standard input, as `-` is standard output for --csv and sweep -o: a scene
// another program makes is piped in without a file between them.
bool readsStandardInput(const SceneSource& source) { return source.file == "-"; }

nlohmann::json readStandardInputScene() {
  // Read, a closed descriptor would look like an empty scene ("invalid JSON at line 1, column 1").
  if (::fcntl(STDIN_FILENO, F_GETFD) == -1) {
    throw UsageError(
        "scene -: standard input is closed; give the scene on it (coinroll simulate - < scene.json), or "
        "name the scene file instead of -");
  }
  return scene::readSceneDocument(std::cin, "standard input");
}

}  // namespace

std::pair<nlohmann::json, std::string> loadSceneDocument(const SceneSource& source,
                                                         const std::optional<nlohmann::json>& initial) {
  nlohmann::json document = !source.file                 ? scene::builtInDefaultScene()
                            : readsStandardInput(source) ? readStandardInputScene()
                                                         : scene::readSceneDocument(*source.file);
  scene::applyOverrides(document, source.overrides, initial);
  const std::string sourceName = !source.file                 ? "built-in default scene"
                                 : readsStandardInput(source) ? "standard input"
                                                              : *source.file;
  return {std::move(document), sourceName};
}

void refuseOverwritingInput(const std::string& option, const std::filesystem::path& output,
                            const std::vector<std::filesystem::path>& inputs) {
  try {
    video::refuseOverwritingInput(option, output, inputs);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

std::vector<std::filesystem::path> inputsOf(const SceneSource& source) {
  if (!readsStandardInput(source)) {
    return pipeline::inputFiles(source.file ? std::optional<std::filesystem::path>(*source.file) : std::nullopt);
  }
  // A file redirected in is read like a named one, so no output may replace it; a pipe or a
  // terminal has nothing to replace (and /dev/null, often standard input, stays writable).
  std::optional<std::filesystem::path> redirected;
  struct stat info {};
  if (::fstat(STDIN_FILENO, &info) == 0 && S_ISREG(info.st_mode)) redirected = "/dev/stdin";
  return pipeline::inputFiles(redirected);
}

void refuseEmptyOutputName(const std::string& option, const std::string& name, const std::string& example) {
  if (name.empty()) {
    throw UsageError(
        fmt::format("{}: the output name is empty; give a file name, e.g. {} {}", option, option, example));
  }
}

std::string sceneDigestOf(const nlohmann::json& document) {
  const std::string canonical = document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return fmt::format("fnv1a64:{:016x}", io::fnv1a64(canonical));
}

namespace {

// A default output name made from the scene name (docs/outputs.md): a name of letters, digits,
// '-', '_' and '.' that does not start with a dot is used as it is; any other ("My scene: v2",
// ".hidden", a Cyrillic name) has each other byte and a leading dot replaced by '_', is cut to
// kMaxDerivedNameBytes, and gets '+' and 8 hex digits of a hash of the whole original name:
// "My_scene__v2+1c0e3f52". So different names never share a file ('+' never survives the
// replacement, so a hashed name cannot equal a kept one; two hashed ones clash only if both the
// replaced text and 32 bits of hash agree), no default name is a hidden file, and every one fits
// in a file name with its extension.
constexpr std::size_t kMaxDerivedNameBytes = 200;

std::string fileNameFrom(const std::string& sceneName) {
  if (sceneName.empty()) return "coinroll";
  std::string name = sceneName;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  if (name[0] == '.') name[0] = '_';
  if (name == sceneName && name.size() <= kMaxDerivedNameBytes) return name;
  name.resize(std::min(name.size(), kMaxDerivedNameBytes));
  const std::uint64_t hash = io::fnv1a64(sceneName);
  return fmt::format("{}+{:08x}", name, static_cast<std::uint32_t>(hash ^ (hash >> 32)));
}

}  // namespace

// What an output is named after without -o: the scene's name, or, for a scene file that gives none,
// the file's own name (two unnamed scenes rendered in one directory no longer both write
// coinroll.mp4, the second replacing the first); the built-in scene's name is "coinroll". A scene
// read from a stream (standard input, a pipe) has no name of its own to lend.
std::filesystem::path defaultOutputName(bool named, const std::string& sceneName, const SceneSource& source,
                                        std::string_view extension) {
  std::error_code error;
  const std::string stem =
      named || !source.file || readsStandardInput(source) || !std::filesystem::is_regular_file(*source.file, error)
          ? sceneName
          : std::filesystem::path(*source.file).stem().string();
  return fileNameFrom(stem) + std::string(extension);
}

void refuseTakingOverDefaultName(
    const std::filesystem::path& output, const std::string& digest,
    const std::function<std::optional<std::string>(const std::filesystem::path&)>& readDigest) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(output, error)) return;
  const std::optional<std::string> existing = readDigest(output);
  if (existing == digest) return;
  const std::string made =
      existing ? fmt::format("made from another scene (its digest {}, this scene's {})", *existing, digest)
               : std::string("does not say which scene made it (no coinroll provenance)");
  throw UsageError(
      fmt::format("{}: exists, {}, and is only this scene's default output name; give -o NAME to write "
                  "elsewhere, or --force to replace it",
                  scene::printable(output.string()), made));
}

void finishStandardOutput(std::string_view what) {
  std::cout.flush();
  // A full device, a closed stdout or a reader gone while SIGPIPE is ignored: the stream says so.
  if (!std::cout)
    throw std::runtime_error(fmt::format("writing the {} to stdout failed: {}", what, std::strerror(errno)));
}

void writeTextOutput(const std::string& path, std::string_view what, const std::function<void(std::ostream&)>& write) {
  if (path == "-") {
    write(std::cout);
    finishStandardOutput(what);
    return;
  }
  io::OutputFile file(path, std::string(what));
  write(file.stream());
  file.commit();
}

}  // namespace coinroll::cli
