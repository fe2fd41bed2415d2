#include "pipeline/trajectory_csv.h"

#include <iterator>

namespace coinroll::pipeline {

std::string trajectoryCsvHeader(std::span<const std::string_view> columns) {
  return fmt::format("{}\n", fmt::join(columns, ","));
}

std::string_view TrajectoryCsvLine::operator()(std::span<const double> values) {
  line_.clear();
  // 17 significant digits round-trip every double (the sliding flag, 0 or 1, prints as such).
  fmt::format_to(std::back_inserter(line_), "{:.17g}\n", fmt::join(values, ","));
  return {line_.data(), line_.size()};
}

TrajectoryReport writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out) {
  out << trajectoryCsvHeader(trajectoryColumns(simulation));
  TrajectoryCsvLine line;
  return sampleTrajectory(simulation, sampleDt, [&](std::span<const double> values) {
    const std::string_view text = line(values);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace coinroll::pipeline
