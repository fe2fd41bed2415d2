#include "pipeline/scene_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "physics/validity.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

namespace {

RunEnd endOf(const TrajectoryReport& run, double duration) {
  if (!run.stoppedBy) return {.event = "duration", .time = duration, .description = {}};
  return {.event = physics::eventName(run.stoppedBy->event),
          .time = run.stoppedBy->t,
          .description = describeStop(*run.stoppedBy)};
}

std::vector<RunMark> marksOf(const TrajectoryReport& run) {
  std::vector<RunMark> marks;
  for (const ModeSwitch& w : run.switches) {
    marks.push_back({.kind = "switch", .name = w.toSliding ? "slides" : "rolls", .time = w.t, .description = {}});
  }
  for (const RunEvent& w : run.warnings) {
    marks.push_back(
        {.kind = "warning", .name = physics::eventName(w.event), .time = w.t, .description = describeStop(w)});
  }
  // Stable: at one time a switch comes before a warning, as the report prints them.
  std::stable_sort(marks.begin(), marks.end(), [](const RunMark& a, const RunMark& b) { return a.time < b.time; });
  // Last whatever its time: a switch or a warning never follows the stop.
  if (const auto& stop = run.stoppedBy) {
    marks.push_back(
        {.kind = "stop", .name = physics::eventName(stop->event), .time = stop->t, .description = describeStop(*stop)});
  }
  return marks;
}

}  // namespace

SceneTable simulateScene(const scene::SceneConfig& scene, const SceneRunRequest& request, const RowSink& sink) {
  const double sampleDt = request.sampleDt;
  if (!(sampleDt > 0) || !std::isfinite(sampleDt)) {
    throw std::invalid_argument(
        fmt::format("{}: must be a finite number > 0 s, got {}", request.sampleDtName, sampleDt));
  }
  // Built before the row limit, whose refusal may say what the rows would take, which depends on
  // the columns the simulation has.
  Simulation simulation = buildSimulation(scene);
  SceneTable table;
  table.start.columns = trajectoryColumns(simulation);
  const std::string rowsCost =
      request.rowsCost ? request.rowsCost(sampleCountUnbounded(scene.duration, sampleDt), table.start.columns.size())
                       : std::string();
  refuseTooManyRows(scene.duration, sampleDt, request.maxRows, request.sampleDtName, request.maxRowsOption, rowsCost);
  simulation.cancel = request.cancel;
  table.start.expectedRows = sampleCount(scene.duration, sampleDt);
  table.start.model = &simulation.model;
  if (const std::string note = steadyStartNote(scene); !note.empty()) {
    table.start.notes.push_back("coinroll: note: " + note);
  }

  if (sink.begin) sink.begin(table.start);
  table.run = sampleTrajectory(simulation, sampleDt, sink.row, sink.sample);
  table.end = endOf(table.run, scene.duration);
  table.marks = marksOf(table.run);
  table.report = reportLines(table.run);
  return table;
}

}  // namespace coinroll::pipeline
