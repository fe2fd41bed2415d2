#include "pipeline/trajectory_samples.h"

#include <cmath>

#include "pipeline/coin_run.h"

namespace coinroll::pipeline {

long sampleCount(double duration, double sampleDt) {
  return static_cast<long>(std::floor(duration / sampleDt * (1 + 1e-9))) + 1;
}

namespace {

bool isDissipative(const Simulation& simulation) { return !simulation.model.effects.empty() || simulation.sliding; }

}  // namespace

std::vector<std::string_view> trajectoryColumns(const Simulation& simulation) {
  std::vector<std::string_view> names(kTrajectoryColumns.begin(), kTrajectoryColumns.end());
  if (isDissipative(simulation)) names.insert(names.end(), kDissipationColumns.begin(), kDissipationColumns.end());
  if (simulation.sliding) names.insert(names.end(), kSlidingColumns.begin(), kSlidingColumns.end());
  return names;
}

TrajectoryReport sampleTrajectory(const Simulation& simulation, double sampleDt, const TrajectoryRow& row) {
  const bool dissipative = isDissipative(simulation);
  CoinRun run(simulation);
  TrajectoryReport result;
  const long rows = sampleCount(simulation.duration, sampleDt);
  std::vector<double> values;
  values.reserve(kTrajectoryColumns.size() + kDissipationColumns.size() + kSlidingColumns.size());
  SingularTimeFit singularTime;
  for (long k = 0; k < rows; ++k) {
    const double t = static_cast<double>(k) * sampleDt;
    const std::optional<RunSample> sample = run.sampleAt(t);
    if (!sample) break;
    const physics::CoinState& s = sample->state;
    const physics::Forward& f = sample->forward;
    const physics::Reaction& r = f.reaction;
    values = {t, s.theta, s.phi, s.psi, s.omega_X, s.omega_Y, s.omega_Z, s.x, f.centre.y(), s.z,
              f.contactPoint.x(), f.contactPoint.z(), f.energy, r.N, r.F};
    if (dissipative) {
      values.push_back(f.loads.power);
      values.push_back(sample->dissipated);
      singularTime.add(t, f.energy, f.loads.power);
    }
    if (simulation.sliding) {
      values.push_back(f.slip.norm());
      values.push_back(f.sliding ? 1 : 0);
    }
    row(values);
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
