#pragma once
// One run of a scene for the three doors that simulate: `coinroll simulate`, the library's
// coinroll::simulate (and the Python module over it) and the WebAssembly core's simulate. The
// request's refusals, the build, the samples and how the run ended happen here, in one order, so
// that a door keeps only how it spells its arguments, what it makes of the rows (CSV text, columns
// of doubles) and how it reports a failure (an exit code, an exception, an error object).

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/coin_model.h"
#include "pipeline/trajectory_samples.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// What a door asks of a run besides the scene.
struct SceneRunRequest {
  double sampleDt = 0;  // s between rows; refused unless finite and > 0
  // The sample step as the door's user spells it ("--sample-dt", "sampleDt"), in every refusal.
  std::string_view sampleDtName;
  long maxRows = kDefaultMaxRows;  // more rows than this are refused before any work (refuseTooManyRows)
  std::string_view maxRowsOption;  // how the user raises maxRows ("--max-rows"); empty when they cannot
  // What the rows would take, said in the row limit's refusal ("about 150 GB of CSV"); none: nothing.
  std::function<std::string(double rows, std::size_t columns)> rowsCost;
  const std::atomic<bool>* cancel = nullptr;  // when set, the run stops at its next sample with Cancelled
};

// A run that passed every refusal and is about to take its first sample.
struct RunStart {
  std::vector<std::string_view> columns;      // trajectoryColumns: what each row holds, in order
  long expectedRows = 0;                      // sampleCount: the rows of a run that reaches its duration
  std::vector<std::string> notes;             // stderr lines about the scene itself ("coinroll: note: ...")
  const physics::CoinModel* model = nullptr;  // the run's coin, valid until simulateScene returns
};

// Where the rows go. `begin` is called once, after the refusals and before the first row, so a door
// opens its output only for a run that will be made; then `row` once per sample.
struct RowSink {
  std::function<void(const RunStart&)> begin;
  TrajectoryRow row;
  SampleObserver sample = {};  // optional: each row's sample itself, before its row, and the duration's
};

// How a run ended: at its duration, or at the validity event that stopped it early.
struct RunEnd {
  std::string_view event;   // "duration", else the event's name ("coin-flat", "lift-off", ...)
  double time = 0;          // s: the scene's duration, or the event's time
  std::string description;  // what `coinroll simulate` prints after "stopped early: "; empty at duration
};

// A moment of the run a page or a log marks.
struct RunMark {
  std::string_view kind;    // "switch" (rolling <-> sliding), "warning" (on_invalid "warn") or "stop"
  std::string_view name;    // "slides" or "rolls" for a switch, else the event's name
  double time = 0;          // s
  std::string description;  // describeStop for a warning or the stop; empty for a switch
};

// A run as every door reports it.
struct SceneTable {
  RunStart start;
  RunEnd end;
  std::vector<RunMark> marks;       // the switches and warnings in time order, then the stop
  std::vector<std::string> report;  // reportLines: what `coinroll simulate` prints on stderr after the run
  TrajectoryReport run;             // the rest a door may show: rows, impacts, singular time, step counts
};

// Refuses the request (std::invalid_argument naming request.sampleDtName), builds `scene`'s
// simulation (scene::SceneError for what only physics can judge), refuses more rows than
// request.maxRows, then samples the run at t = k sampleDt into `sink` and takes it on to its duration,
// so that a stop after the last row is still how it ended.
SceneTable simulateScene(const scene::SceneConfig& scene, const SceneRunRequest& request, const RowSink& sink);

}  // namespace coinroll::pipeline
