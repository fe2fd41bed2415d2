#pragma once
// The trajectory as data: the contract's columns sampled at t = k S from the dense output, handed
// row by row to whoever keeps them. The CSV writer (trajectory_csv.h), the C++ API, the Python
// module and the WebAssembly module are views of these rows, so a column is defined here once.

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "integrate/events.h"
#include "pipeline/hybrid_run.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"
#include "pipeline/singular_time.h"

namespace coinroll::pipeline {

// The contract's fixed columns (docs/contract.md §3), in order.
inline constexpr std::array<std::string_view, 15> kTrajectoryColumns = {
    "t", "theta", "phi",       "psi",       "omega_X", "omega_Y",      "omega_Z",       "x",
    "y", "z",     "contact_x", "contact_z", "energy",  "normal_force", "friction_force"};
// After them when the scene has effects or slides: power dissipated now (W) and since t = 0 (J).
inline constexpr std::array<std::string_view, 2> kDissipationColumns = {"power", "dissipated"};
// With "sliding": true, after those: the contact point's slip speed and 1 while sliding, else 0.
inline constexpr std::array<std::string_view, 2> kSlidingColumns = {"slip_speed", "sliding"};

// With "flight": true, after those: 0 rolling, 1 sliding, 2 in flight; and the impacts so far.
inline constexpr std::array<std::string_view, 2> kFlightColumns = {"phase", "impacts"};

// The columns a run of `simulation` has, in order.
std::vector<std::string_view> trajectoryColumns(const Simulation& simulation);

// Number of rows for a duration and sample step: k = 0 .. floor(duration / S). The quotient is
// nudged by a relative 1e-9 so a duration that is a whole number of steps keeps its last row
// despite round-off: 2.3 / 0.01 is 229.99999999999997 in binary, which alone would give 230 rows
// instead of 231.
long sampleCount(double duration, double sampleDt);

// Rows above this need the command's --max-rows: 10^8 rows is about 30 GB of CSV and minutes of
// sampling, and more than most machines hold in memory for the library's columns, so a sample step
// with a few zeros too many (1e-9 on a 0.5 s run: 5e8 rows) is refused up front. Counted from the
// duration, before the run: a spin-down given a huge duration "until it stops" (1e5 s at 0.01 s is
// 10^7 rows) must still pass, though it has only the rows before its coin-flat stop.
inline constexpr long kDefaultMaxRows = 100'000'000;

// sampleCount in a double, for a limit checked before the run: an absurd request (1e6 s at
// 1e-300 s) has more rows than a long holds. Exact, and equal to sampleCount, below 2^53.
double sampleCountUnbounded(double duration, double sampleDt);

// Refuses with std::invalid_argument, before any work, sampling `duration` s every `sampleDt` s in
// more than `maxRows` rows, counted as the run writes them (a whole number). The message names the
// sample step as the caller's user gives it (`sampleDtName`: "--sample-dt", "sampleDt"), how they
// raise the limit (`maxRowsOption`: "--max-rows"; empty when they cannot), and what the rows would
// take (`rowsCost`, e.g. "about 150 GB of CSV"; empty for nothing).
void refuseTooManyRows(double duration, double sampleDt, long maxRows, std::string_view sampleDtName,
                       std::string_view maxRowsOption, std::string_view rowsCost = {});

// A scene without `friction` has no cone to leave (ideal rolling): the most friction per unit of
// normal force its rolling contact needed, so a reader knows which mu it takes (docs/sliding.md §4.7).
struct FrictionNeeded {
  double ratio = 0;  // the largest |F| / N over the samples in contact (and the stop)
  double t = 0;      // s, where it was reached
};

// How a sampled run went.
struct TrajectoryReport {
  long rows = 0;
  std::optional<RunEvent> stoppedBy;
  std::vector<RunEvent> warnings;                    // on_invalid "warn": crossings gone past
  std::vector<ModeSwitch> switches;                  // "sliding": true: each switch between rolling and sliding
  std::vector<ImpactRecord> impacts;                 // "flight": true: each impact of the rim
  bool flight = false;                               // "flight": true: a run that ends lying on a face says which
  std::optional<SingularTimeEstimate> singularTime;  // a spin-down that reached coin-flat or face-down
  std::optional<FrictionNeeded> frictionNeeded;      // no `friction` in the scene: the cone it needed
  integrate::Stats stats;
};

// Integrates `simulation` and hands `row` the values of trajectoryColumns(simulation) at each
// sample time, until the duration or the event that ends the run.
// `observe`, when set, sees each row's sample itself before the row (`row` true; the visual track's
// source), and the sample at the duration the run is taken on to after the last row (`row` false).
using TrajectoryRow = std::function<void(std::span<const double>)>;
using SampleObserver = std::function<void(double t, const RunSample&, bool row)>;
TrajectoryReport sampleTrajectory(const Simulation& simulation, double sampleDt, const TrajectoryRow& row,
                                  const SampleObserver& observe = {});

// What `coinroll simulate` prints on stderr about a run, a line each, without line breaks: the
// switches, the impacts and the warnings merged in simulated-time order (at one time: switch, impact,
// warning), then the stop, the face it lies on, the singular time, the friction a scene without
// `friction` needed, and the counts. The WebAssembly
// core returns the same lines.
std::vector<std::string> reportLines(const TrajectoryReport& report);

}  // namespace coinroll::pipeline
