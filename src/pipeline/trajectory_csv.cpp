#include "pipeline/trajectory_csv.h"

#include <fmt/format.h>

#include <iterator>

namespace coinroll::pipeline {

TrajectoryReport writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out) {
  out << fmt::format("{}\n", fmt::join(trajectoryColumns(simulation), ","));
  fmt::memory_buffer line;
  return sampleTrajectory(simulation, sampleDt, [&](std::span<const double> values) {
    line.clear();
    // 17 significant digits round-trip every double (the sliding flag, 0 or 1, prints as such).
    fmt::format_to(std::back_inserter(line), "{:.17g}\n", fmt::join(values, ","));
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  });
}

}  // namespace coinroll::pipeline
