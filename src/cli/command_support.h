#pragma once
// What the commands share: the scene a command reads, the checks on its output's name, writing
// text to a file or standard output, and the progress line with the failures it maps.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/interrupts.h"
#include "cli/progress.h"
#include "pipeline/cancelled.h"

namespace coinroll::cli {

// The scene document with --set applied, and the name its messages use. A given `initial`
// replaces the scene's initial block before the --set ones apply, so that --set initial.phi=45
// lands on it instead of being replaced by it (steady --kind).
std::pair<nlohmann::json, std::string> loadSceneDocument(const SceneSource& source,
                                                         const std::optional<nlohmann::json>& initial = std::nullopt);

// An output must never replace a file the command reads: refused before anything runs.
void refuseOverwritingInput(const std::string& option, const std::filesystem::path& output,
                            const std::vector<std::filesystem::path>& inputs);

// The files a command reads: its scene, and the files of $COINROLL_ASSET_DIR and
// $COINROLL_SHADER_DIR when set (a texture or a shader the output must not replace).
std::vector<std::filesystem::path> inputsOf(const SceneSource& source);

// An empty output name would be found only when the output is opened, which for some commands
// is after all the work: refused first, naming the option and what to give.
void refuseEmptyOutputName(const std::string& option, const std::string& name, const std::string& example);

// The scene's digest as its outputs carry it (docs/outputs.md "Provenance"): FNV-1a of the resolved
// document as compact JSON, keys sorted, "fnv1a64:0123456789abcdef".
std::string sceneDigestOf(const nlohmann::json& document);

// The name of an output the user did not name (no -o): the scene's name, or its file's when it
// gives none, made a safe file name (docs/outputs.md), and `extension` (".mp4").
std::filesystem::path defaultOutputName(bool named, const std::string& sceneName, const SceneSource& source,
                                        std::string_view extension);

// A name the program chose for an output (the user gave no -o) may already hold a file: it is
// replaced only when made from the same scene, `readDigest(output)` (the scene digest the file
// carries, none for a file that names no scene) equal to `digest`; otherwise refused, naming -o and
// --force, so one scene's output never silently takes over another's. Only a regular file is read:
// a device or FIFO under the name gets the output as it would under -o (io/output_file.h).
void refuseTakingOverDefaultName(
    const std::filesystem::path& output, const std::string& digest,
    const std::function<std::optional<std::string>(const std::filesystem::path&)>& readDigest);

// Flushes standard output once `what` ("CSV") is written to it; std::runtime_error if the stream
// failed (a full device, a closed stdout, a reader gone while SIGPIPE is ignored).
void finishStandardOutput(std::string_view what);

// Runs `write` into `path`: standard output for "-", otherwise the output layer (a temporary file
// that takes the name only once `write` and the close have succeeded, or a device, FIFO or
// descriptor written directly; io/output_file.h). `what` names the content in errors ("CSV").
void writeTextOutput(const std::string& path, std::string_view what, const std::function<void(std::ostream&)>& write);

// Runs a long command's work with its progress line, ending the line however the work ends, and
// maps the ways it fails alike for every command: Ctrl-C (after `discardOutput`, which removes
// a partial output the caller holds) to exit 1 saying nothing was written, a bad request to
// exit 2.
template <class Work>
auto withProgress(ProgressLine& progress, const std::string& output, Work work,
                  const std::function<void()>& discardOutput = {}) -> decltype(work()) {
  try {
    auto result = work();
    progress.finish();
    return result;
  } catch (const pipeline::Cancelled&) {
    progress.finish();
    if (discardOutput) discardOutput();
    throw std::runtime_error(interruptionMessage(output));
  } catch (const std::invalid_argument& e) {
    progress.finish();
    throw UsageError(e.what());
  } catch (...) {
    progress.finish();
    throw;
  }
}

}  // namespace coinroll::cli
