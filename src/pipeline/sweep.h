#pragma once
// Parameter sweeps (docs/contract.md §7): the Cartesian grid over scene fields, one summary row
// per point, computed by a pool of threads inside one process and written in point order, so the
// bytes do not depend on the thread count or on how the grid is split into shards.

#include <nlohmann/json.hpp>

#include <atomic>
#include <functional>
#include <ostream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/sweep_grid.h"
#include "scene/scene_loader.h"

namespace coinroll::pipeline {

// Points above this need --max-points: a typo in a COUNT should not start a week-long run.
inline constexpr long kDefaultMaxPoints = 10'000'000;

struct SweepSpec {
  nlohmann::json scene;    // the scene document, --set overrides applied
  std::string sourceName;  // names the scene in the messages of failed points
  std::vector<GridAxis> axes;
  Shard shard;
  int threads = 1;
  long maxPoints = kDefaultMaxPoints;
};

// The header's columns after the grid keys: the contract's six, then theta_end, which tells a
// toss's face (theta < 0: heads).
inline constexpr std::string_view kSweepSummaryColumns =
    ",end,t_end,theta_min,theta_max,energy_start,energy_end,theta_end";
// The header's last two columns, after the summary's: SweepIdentity.
inline constexpr std::string_view kSweepIdentityColumns = ",grid_points,sweep";

// "point,<keys>,end,t_end,theta_min,theta_max,energy_start,energy_end,theta_end,grid_points,sweep":
// the contract's columns, theta_end, then the sweep's identity (SweepIdentity).
std::string sweepHeader(const std::vector<GridAxis>& axes);

// A grid key that names no field, or names one twice, would give a whole grid of identical or
// failed rows; both are typos, refused here with std::invalid_argument before any work. A value
// that is wrong at some points is not: those rows carry their error.
void refuseMisnamedAxes(const SweepSpec& spec);

// Points in the whole grid; throws std::invalid_argument naming --grid when it exceeds maxPoints.
long gridPointCount(const SweepSpec& spec);

// What every row of a sweep carries after the contract's columns, the same in every shard and in
// the unsharded file (so merged shards still equal it byte for byte): the number of points in the
// whole grid, which lets a merge find points missing at the grid's top, and 16 hexadecimal
// digits of FNV-1a over the scene document (after --set, keys sorted) and every axis' key and
// values, which tells shards of different sweeps apart. The shard K/N is not part of it.
struct SweepIdentity {
  long gridPoints = 0;
  std::string digest;
};
SweepIdentity sweepIdentity(const SweepSpec& spec);

// One point of the grid, as computed.
struct SweepPoint {
  long point = 0;
  std::vector<double> values;  // each axis' value at the point, in the axes' order
  std::string end;             // "duration", the event that ended the run, or "error: <the loader's or run's message>"
  bool failed = false;         // `end` is an error; the numbers below are then NaN
  double tEnd = 0;             // s
  double thetaMin = 0, thetaMax = 0;      // rad, over samples every 0.01 s and the last state
  double energyStart = 0, energyEnd = 0;  // J
  double thetaEnd = 0;                    // rad, of the last state: at the event that ended the run, or the duration
};

struct SweepResult {
  long points = 0;                   // rows handed on
  long failed = 0;                   // points whose end is an error
  std::map<std::string, long> ends;  // how the other points ended: "duration", "coin-flat", ... and their counts
};

// Simulates every point of the shard and hands them to `row` in point order. A point whose scene
// is invalid or whose integration fails carries "error: <reason>" in its end. `onPoint(done,
// total)` is called as each point finishes, by the thread that computed it, one call at a time; a
// set `cancel` stops the sweep between points with Cancelled. Points are computed in blocks, so
// memory does not grow with the number of points.
SweepResult runSweep(const SweepSpec& spec, const std::function<void(const SweepPoint&)>& row,
                     const std::function<void(long, long)>& onPoint, const std::atomic<bool>* cancel);

// runSweep's points as the sweep CSV (docs/sweeps.md): sweepHeader, then one row per point with
// the sweep's identity.
SweepResult writeSweepCsv(const SweepSpec& spec, std::ostream& out, const std::function<void(long, long)>& onPoint,
                          const std::atomic<bool>* cancel);

}  // namespace coinroll::pipeline
