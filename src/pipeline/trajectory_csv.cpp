#include "pipeline/trajectory_csv.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "pipeline/coin_run.h"
#include "pipeline/singular_time.h"

namespace coinroll::pipeline {

long sampleCount(double duration, double sampleDt) {
  return static_cast<long>(std::floor(duration / sampleDt * (1 + 1e-9))) + 1;
}

CsvRunResult writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out) {
  const bool dissipative = !simulation.model.effects.empty() || simulation.sliding;
  out << kCsvHeader << (dissipative ? kCsvDissipationColumns : "") << (simulation.sliding ? kCsvSlidingColumns : "") << '\n';
  CoinRun run(simulation);
  CsvRunResult result;
  const long rows = sampleCount(simulation.duration, sampleDt);
  fmt::memory_buffer line;
  SingularTimeFit singularTime;
  for (long k = 0; k < rows; ++k) {
    const double t = static_cast<double>(k) * sampleDt;
    const std::optional<RunSample> sample = run.sampleAt(t);
    if (!sample) break;
    const physics::CoinState& s = sample->state;
    const physics::Forward& f = sample->forward;
    const Eigen::Vector3d& centre = f.centre;
    const Eigen::Vector3d& contact = f.contactPoint;
    const physics::Reaction& r = f.reaction;
    const double energy = f.energy;
    line.clear();
    // 17 significant digits round-trip every double: the CSV is a faithful copy of the state.
    fmt::format_to(std::back_inserter(line), "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},",
                   t, s.theta, s.phi, s.psi, s.omega_X, s.omega_Y, s.omega_Z, s.x);
    fmt::format_to(std::back_inserter(line), "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}",
                   centre.y(), s.z, contact.x(), contact.z(), energy, r.N, r.F);
    if (dissipative) {
      fmt::format_to(std::back_inserter(line), ",{:.17g},{:.17g}", f.loads.power, sample->dissipated);
      singularTime.add(t, energy, f.loads.power);
    }
    if (simulation.sliding) fmt::format_to(std::back_inserter(line), ",{:.17g},{:d}", f.slip.norm(), f.sliding ? 1 : 0);
    line.push_back('\n');
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
    ++result.rows;
  }
  result.stoppedBy = run.stoppedBy();
  const bool flat = result.stoppedBy && (result.stoppedBy->event == physics::ModelEvent::CoinFlat ||
                                         result.stoppedBy->event == physics::ModelEvent::FaceDown);
  if (!simulation.model.effects.empty() && flat) {
    // The stop itself is the sample nearest the singularity; the fit needs it most.
    singularTime.add(result.stoppedBy->t, result.stoppedBy->forward.energy, result.stoppedBy->forward.loads.power);
    result.singularTime = singularTime.estimate();
  }
  result.warnings = run.warnings();
  result.switches = run.switches();
  result.stats = run.stats();
  return result;
}

}  // namespace coinroll::pipeline
