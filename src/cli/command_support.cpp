#include "cli/command_support.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>

#include "io/output_file.h"
#include "scene/scene_loader.h"
#include "video/make_sink.h"
#include "video/png_sequence_sink.h"

namespace coinroll::cli {

std::pair<nlohmann::json, std::string> loadSceneDocument(const SceneSource& source,
                                                         const std::optional<nlohmann::json>& initial) {
  nlohmann::json document = source.file ? scene::readSceneDocument(*source.file) : scene::builtInDefaultScene();
  // A document that is no object has no initial block to replace: the loader names what it is.
  if (initial && document.is_object()) document["initial"] = *initial;
  for (const std::string& assignment : source.overrides) scene::applyOverride(document, assignment);
  return {std::move(document), source.file ? *source.file : "built-in default scene"};
}

namespace {

// The frame names of `output` when it names a PNG sequence with a well-formed pattern; a malformed
// one is the sink's to refuse, naming the rule it breaks.
std::optional<video::SequencePattern> sequencePatternOf(const std::filesystem::path& output) {
  if (!video::namesPngSequence(output)) return std::nullopt;
  try {
    return video::parseSequencePattern(output);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

}  // namespace

void refuseOverwritingInput(const std::string& option, const std::filesystem::path& output,
                            const std::vector<std::filesystem::path>& inputs) {
  std::error_code error;
  const std::optional<video::SequencePattern> frames = sequencePatternOf(output);
  for (const std::filesystem::path& input : inputs) {
    const std::filesystem::path outputDirectory = output.parent_path().empty() ? "." : output.parent_path();
    const std::filesystem::path inputDirectory = input.parent_path().empty() ? "." : input.parent_path();
    if (frames && std::filesystem::equivalent(outputDirectory, inputDirectory, error) &&
        frames->frameNumberOf(input.filename().string())) {
      throw UsageError(fmt::format("{} {}: one of its frames would be the input {}; choose another output name", option,
                                   output.string(), input.string()));
    }
    if (std::filesystem::equivalent(output, input, error)) {
      throw UsageError(fmt::format("{} {}: that is the input {}; choose another output name", option, output.string(),
                                   input.string()));
    }
  }
}

std::vector<std::filesystem::path> inputsOf(const SceneSource& source) {
  std::vector<std::filesystem::path> inputs;
  if (source.file) inputs.emplace_back(*source.file);
  for (const char* variable : {"COINROLL_ASSET_DIR", "COINROLL_SHADER_DIR"}) {
    const char* directory = std::getenv(variable);
    if (directory == nullptr || *directory == '\0') continue;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
      if (entry.is_regular_file(error)) inputs.push_back(entry.path());
    }
  }
  return inputs;
}

void refuseEmptyOutputName(const std::string& option, const std::string& name, const std::string& example) {
  if (name.empty()) {
    throw UsageError(
        fmt::format("{}: the output name is empty; give a file name, e.g. {} {}", option, option, example));
  }
}

void writeTextOutput(const std::string& path, std::string_view what, const std::function<void(std::ostream&)>& write) {
  if (path == "-") {
    write(std::cout);
    std::cout.flush();
    // A full device, a closed stdout or a reader gone while SIGPIPE is ignored: the stream says so.
    if (!std::cout)
      throw std::runtime_error(fmt::format("writing the {} to stdout failed: {}", what, std::strerror(errno)));
    return;
  }
  io::OutputFile file(path, std::string(what));
  write(file.stream());
  file.commit();
}

}  // namespace coinroll::cli
