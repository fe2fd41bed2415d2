#pragma once
// The grid of a sweep (docs/contract.md §7): its --grid axes and the --shard that picks a slice
// of its points, parsed from the command line's text.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace coinroll::pipeline {

// One --grid axis over a scene field, in the scene file's units:
//   KEY.PATH=START:STOP:COUNT      COUNT evenly spaced values, START and STOP included
//   KEY.PATH=START:STOP:COUNT:log  COUNT geometrically spaced values (START, STOP > 0)
//   KEY.PATH=V1,V2,V3              the values listed, in their order
struct GridAxis {
  enum class Spacing { Even, Geometric, Listed };
  std::string key;  // e.g. "initial.theta", as for --set
  Spacing spacing = Spacing::Even;
  double start = 0, stop = 0;  // Even and Geometric
  long count = 1;
  std::vector<double> listed;  // Listed: the values, count of them

  // The i-th of the axis' `count` values; exactly START at 0 and STOP at count - 1.
  double valueAt(long i) const;
};

// Throws std::invalid_argument naming --grid and the rule for a malformed axis.
GridAxis parseGridAxis(std::string_view text);

// --shard K/N: the points p with p mod N = K - 1.
struct Shard {
  long index = 1;  // K, 1-based
  long count = 1;  // N
};

// --shard K/N, or auto/N with K the Slurm array task's number (`slurmArrayTaskId`, the value of
// $SLURM_ARRAY_TASK_ID, absent outside an array task). Throws std::invalid_argument naming --shard
// for anything but 1 <= K <= N.
Shard parseShard(std::string_view text, std::optional<std::string_view> slurmArrayTaskId);

}  // namespace coinroll::pipeline
