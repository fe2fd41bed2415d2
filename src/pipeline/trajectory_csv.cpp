#include "pipeline/trajectory_csv.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "physics/observables.h"
#include "pipeline/coin_run.h"

namespace coinroll::pipeline {

long sampleCount(double duration, double sampleDt) {
  return static_cast<long>(std::floor(duration / sampleDt * (1 + 1e-9))) + 1;
}

CsvRunResult writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out) {
  out << kCsvHeader << '\n';
  CoinRun run(simulation);
  CsvRunResult result;
  const long rows = sampleCount(simulation.duration, sampleDt);
  fmt::memory_buffer line;
  for (long k = 0; k < rows; ++k) {
    const double t = static_cast<double>(k) * sampleDt;
    const std::optional<physics::CoinState> state = run.stateAt(t);
    if (!state) break;
    const physics::CoinState& s = *state;
    const Eigen::Vector3d centre = physics::centreOfMass(simulation.model, s);
    const Eigen::Vector3d contact = physics::contactPoint(simulation.model, s);
    const physics::Reaction r = physics::reaction(simulation.model, s);
    line.clear();
    // 17 significant digits round-trip every double: the CSV is a faithful copy of the state.
    fmt::format_to(std::back_inserter(line), "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},",
                   t, s.theta, s.phi, s.psi, s.omega_X, s.omega_Y, s.omega_Z, s.x);
    fmt::format_to(std::back_inserter(line), "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n",
                   centre.y(), s.z, contact.x(), contact.z(), physics::energy(simulation.model, s), r.N, r.F);
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
    ++result.rows;
  }
  result.stoppedBy = run.stoppedBy();
  result.stats = run.stats();
  return result;
}

}  // namespace coinroll::pipeline
