#pragma once
// Merging the shard files of one sweep (docs/contract.md §7) into the file the unsharded sweep
// writes, byte for byte.

#include <atomic>
#include <filesystem>
#include <ostream>
#include <vector>

namespace coinroll::pipeline {

// Concatenates shard files in point order after checking that they share one header with this
// coinroll's summary columns (an older coinroll's shard, without theta_end, is refused), that every
// row belongs to one sweep (SweepIdentity), that no file was cut short and that every point of the
// grid is there exactly once. A shard may be a pipe or a FIFO, or "-" for standard input, and may
// hold only the header (a shard with no points). Every cell must be of its column's type. Throws
// std::runtime_error naming the file and line (and the column), or the repeated or missing points;
// a set `cancel` stops the reading with Cancelled. Returns the number of points merged.
long mergeSweepShards(const std::vector<std::filesystem::path>& shards, std::ostream& out,
                      const std::atomic<bool>* cancel = nullptr);

}  // namespace coinroll::pipeline
