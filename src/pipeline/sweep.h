#pragma once
// Parameter sweeps (INTERFACE.md "Sweeps"): the Cartesian grid over scene fields, one summary row
// per point, computed by a pool of threads inside one process and written in point order, so the
// bytes do not depend on the thread count or on how the grid is split into shards.

#include <nlohmann/json.hpp>

#include <atomic>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_loader.h"

namespace coinroll::pipeline {

// One --grid KEY.PATH=START:STOP:COUNT axis, in the scene file's units.
struct GridAxis {
  std::string key;  // e.g. "initial.theta", as for --set
  double start = 0, stop = 0;
  long count = 1;

  // The i-th of `count` evenly spaced values; exactly start at 0 and stop at count - 1.
  double valueAt(long i) const;
};

// Throws std::invalid_argument naming --grid and the rule for a malformed axis.
GridAxis parseGridAxis(std::string_view text);

// --shard K/N: the points p with p mod N = K - 1.
struct Shard {
  long index = 1;  // K, 1-based
  long count = 1;  // N
};

// Throws std::invalid_argument naming --shard for anything but 1 <= K <= N.
Shard parseShard(std::string_view text);

// Points above this need --max-points: a typo in a COUNT should not start a week-long run.
inline constexpr long kDefaultMaxPoints = 10'000'000;

struct SweepSpec {
  nlohmann::json scene;      // the scene document, --set overrides applied
  std::string sourceName;    // names the scene in the messages of failed points
  scene::ParseOptions parseOptions;
  std::vector<GridAxis> axes;
  Shard shard;
  int threads = 1;
  long maxPoints = kDefaultMaxPoints;
};

// "point,<keys>,end,t_end,theta_min,theta_max,energy_start,energy_end".
std::string sweepHeader(const std::vector<GridAxis>& axes);

// Points in the whole grid; throws std::invalid_argument naming --grid when it exceeds maxPoints.
long gridPointCount(const SweepSpec& spec);

struct SweepResult {
  long points = 0;  // rows written
  long failed = 0;  // rows whose end column holds an error
};

// Simulates every point of the shard and writes the header and the rows to `out`, in point order.
// A point whose scene is invalid or whose integration fails gets "error: <reason>" in its end
// column. `onPoint(done, total)` is called from the writing thread; a set `cancel` stops the
// sweep between points with Cancelled. Rows are computed in blocks, so memory does not grow with
// the number of points.
SweepResult runSweep(const SweepSpec& spec, std::ostream& out, const std::function<void(long, long)>& onPoint,
                     const std::atomic<bool>* cancel);

// Concatenates shard files in point order after checking that they share one header, that no
// point appears twice and that none is missing below the last one. Throws std::runtime_error
// naming the repeated or missing points; a set `cancel` stops the reading with Cancelled.
void mergeSweepShards(const std::vector<std::filesystem::path>& shards, std::ostream& out,
                      const std::atomic<bool>* cancel = nullptr);

}  // namespace coinroll::pipeline
