#include "cli/commands.h"

#include <fmt/format.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <tuple>

#include "cli/command_support.h"
#include "pipeline/sweep.h"
#include "pipeline/sweep_merge.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"

namespace coinroll::cli {

void runSweep(const SweepOptions& options) {
  refuseEmptyOutputName("-o", options.output, "sweep.csv (or - for standard output)");
  if (options.output != "-") refuseOverwritingInput("-o", options.output, inputsOf(options.scene));
  pipeline::SweepSpec spec;
  std::tie(spec.scene, spec.sourceName) = loadSceneDocument(options.scene);
  // The scene must be valid as given: a grid then only varies fields of a scene that works.
  scene::parseScene(spec.scene, spec.sourceName);
  try {
    for (const std::string& axis : options.grid) spec.axes.push_back(pipeline::parseGridAxis(axis));
    pipeline::refuseMisnamedAxes(spec);
    if (options.shard) {
      const char* arrayTaskId = std::getenv("SLURM_ARRAY_TASK_ID");
      spec.shard = pipeline::parseShard(*options.shard,
                                        arrayTaskId ? std::optional<std::string_view>(arrayTaskId) : std::nullopt);
    }
    if (options.maxPoints > 0) spec.maxPoints = options.maxPoints;
    if (options.threads < 0 || options.threads > 1024) {
      throw std::invalid_argument(
          fmt::format("--threads: must be 1 to 1024 (0: every hardware thread), got {}", options.threads));
    }
    pipeline::gridPointCount(spec);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  spec.threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  // In a batch job (Slurm, parallel) stderr is a log file: the progress comes as lines that name the shard.
  ProgressLine progress(
      ProgressLine::styleFor(options.quiet),
      spec.shard.count > 1 ? fmt::format("sweep shard {}/{}", spec.shard.index, spec.shard.count) : "sweep", "point");
  const auto start = std::chrono::steady_clock::now();
  const pipeline::SweepResult result = withProgress(progress, options.output, [&] {
    pipeline::SweepResult r;
    writeTextOutput(options.output, "sweep", [&](std::ostream& out) {
      r = pipeline::writeSweepCsv(
          spec, out, [&](long done, long total) { progress.update(done, total); }, &interruptRequested());
    });
    return r;
  });
  if (!options.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // How the runs ended, not only how many failed: spin-downs that reached the scene's duration
    // without landing would otherwise pass for landed ones in a plot of t_end.
    std::string ends;
    for (const auto& [end, count] : result.ends) ends += fmt::format(", {} {}", count, end);
    std::cerr << fmt::format(
        "coinroll: wrote {} ({} points{}, {} failed{}; {:.1f} s, {:.0f} points/s on {} threads)\n",
        options.output == "-" ? "standard output" : scene::printable(options.output), result.points,
        spec.shard.count > 1 ? fmt::format(", shard {}/{}", spec.shard.index, spec.shard.count) : "", result.failed,
        ends, seconds, result.points / std::max(seconds, 1e-9), spec.threads);
  }
}

void runSweepMerge(const SweepMergeOptions& options) {
  const std::vector<std::filesystem::path> shards(options.shards.begin(), options.shards.end());
  // Checked before any file is opened: a closed descriptor 0 is the first one open() hands out, and
  // then reads as an empty shard (or as the output's temporary file).
  if (std::find(shards.begin(), shards.end(), "-") != shards.end() && ::fcntl(STDIN_FILENO, F_GETFD) == -1) {
    throw std::runtime_error(
        "standard input: closed, so there is no shard to read from it; redirect the shard into it "
        "(- < part.csv) or give its file name instead of -");
  }
  refuseEmptyOutputName("-o", options.output, "merged.csv (or - for standard output)");
  if (std::find(shards.begin(), shards.end(), "") != shards.end()) {
    throw UsageError("a shard name is empty; give the shard files (e.g. part_*.csv), or - for standard input");
  }
  if (options.output != "-") refuseOverwritingInput("-o", options.output, shards);
  ProgressLine noProgress(ProgressLine::Style::Off, "", "");
  const long points = withProgress(noProgress, options.output, [&] {
    long merged = 0;
    writeTextOutput(options.output, "merged sweep", [&](std::ostream& out) {
      merged = pipeline::mergeSweepShards(shards, out, &interruptRequested());
    });
    return merged;
  });
  if (!options.quiet) {
    std::cerr << fmt::format("coinroll: wrote {} ({} points from {} shards)\n",
                             options.output == "-" ? "standard output" : scene::printable(options.output), points,
                             shards.size());
  }
}

}  // namespace coinroll::cli
