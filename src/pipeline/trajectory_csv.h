#pragma once
// The trajectory CSV of docs/contract.md §3: the header, then one row per sample of
// sampleTrajectory, every number with 17 significant digits (each double round-trips).

#include <fmt/format.h>

#include <ostream>
#include <span>
#include <string>
#include <string_view>

#include "pipeline/simulation.h"
#include "pipeline/trajectory_samples.h"

namespace coinroll::pipeline {

// The header line, newline included: the column names, comma-separated.
std::string trajectoryCsvHeader(std::span<const std::string_view> columns);

// Formats rows into one reused buffer, so a door that writes rows as they come (the command to its
// output, the WebAssembly core into its text) allocates nothing per row.
class TrajectoryCsvLine {
 public:
  // The row's line, newline included; valid until the next call.
  std::string_view operator()(std::span<const double> values);

 private:
  fmt::memory_buffer line_;
};

// Integrates `simulation` and writes the header and one row per sample time to `out`.
TrajectoryReport writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out);

}  // namespace coinroll::pipeline
