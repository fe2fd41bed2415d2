#include "pipeline/trajectory_samples.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "pipeline/coin_run.h"

namespace coinroll::pipeline {

long sampleCount(double duration, double sampleDt) {
  return static_cast<long>(sampleCountUnbounded(duration, sampleDt));
}

double sampleCountUnbounded(double duration, double sampleDt) {
  return std::floor(duration / sampleDt * (1 + 1e-9)) + 1;
}

void refuseTooManyRows(double duration, double sampleDt, long maxRows, std::string_view sampleDtName,
                       std::string_view maxRowsOption, std::string_view rowsCost) {
  if (const double rows = sampleCountUnbounded(duration, sampleDt); rows > static_cast<double>(maxRows)) {
    const std::string raise = maxRowsOption.empty()
                                  ? std::string(sampleDtName)
                                  : fmt::format("{}, or the limit with {}", sampleDtName, maxRowsOption);
    const std::string cost = rowsCost.empty() ? std::string() : fmt::format(" ({})", rowsCost);
    throw std::invalid_argument(
        fmt::format("{} {}: duration {} s gives {:.0f} rows{}, more than the limit {}; "
                    "raise {}",
                    sampleDtName, sampleDt, duration, rows, cost, maxRows, raise));
  }
}

namespace {

bool isDissipative(const Simulation& simulation) { return !simulation.model.effects.empty() || simulation.sliding; }

// Without a cone nothing watches |F| <= mu N: the ratio the rolling contact needed is kept instead,
// with the first time it was reached; a later sample must exceed it by more than round-off, or a
// steady motion's time would be whichever sample's last bit came out largest (another libm's differs).
void noteFrictionNeeded(std::optional<FrictionNeeded>& needed, double t, const physics::Forward& f) {
  if (f.flying || f.sliding || !(f.reaction.N > 0)) return;
  const double ratio = f.reaction.F / f.reaction.N;
  if (!needed || ratio > needed->ratio * (1 + 1e-9)) needed = FrictionNeeded{.ratio = ratio, .t = t};
}

}  // namespace

std::vector<std::string_view> trajectoryColumns(const Simulation& simulation) {
  std::vector<std::string_view> names(kTrajectoryColumns.begin(), kTrajectoryColumns.end());
  if (isDissipative(simulation)) names.insert(names.end(), kDissipationColumns.begin(), kDissipationColumns.end());
  if (simulation.sliding) names.insert(names.end(), kSlidingColumns.begin(), kSlidingColumns.end());
  if (simulation.flight) names.insert(names.end(), kFlightColumns.begin(), kFlightColumns.end());
  return names;
}

TrajectoryReport sampleTrajectory(const Simulation& simulation, double sampleDt, const TrajectoryRow& row,
                                  const SampleObserver& observe) {
  const bool dissipative = isDissipative(simulation);
  CoinRun run(simulation);
  TrajectoryReport result;
  const long rows = sampleCount(simulation.duration, sampleDt);
  std::vector<double> values;
  values.reserve(kTrajectoryColumns.size() + kDissipationColumns.size() + kSlidingColumns.size() +
                 kFlightColumns.size());
  SingularTimeFit singularTime;
  for (long k = 0; k < rows; ++k) {
    const double t = static_cast<double>(k) * sampleDt;
    const std::optional<RunSample> sample = run.sampleAt(t);
    if (!sample) break;
    if (observe) observe(t, *sample, true);
    const physics::CoinState& s = sample->state;
    const physics::Forward& f = sample->forward;
    const physics::Reaction& r = f.reaction;
    values = {t,         s.theta, s.phi,        s.psi, s.omega_X,          s.omega_Y,
              s.omega_Z, s.x,     f.centre.y(), s.z,   f.contactPoint.x(), f.contactPoint.z(),
              f.energy,  r.N,     r.F};
    if (dissipative) {
      values.push_back(f.loads.power);
      values.push_back(sample->dissipated);
      // A flying coin's tilt is its tumbling, not a spin-down's approach to the floor.
      if (!f.flying) singularTime.add(t, physics::tiltAboveFloor(f));
    }
    if (simulation.sliding) {
      values.push_back(f.slip.norm());
      values.push_back(f.sliding ? 1 : 0);
    }
    if (simulation.flight) {
      values.push_back(f.flying ? 2 : f.sliding ? 1 : 0);
      values.push_back(sample->impacts);
    }
    if (!simulation.model.friction.cone) noteFrictionNeeded(result.frictionNeeded, t, f);
    row(values);
    ++result.rows;
  }
  // The rows end at the last multiple of the sample step; the run goes on to its duration, and a stop
  // after the last row is still its stop.
  if (result.rows == rows && static_cast<double>(rows - 1) * sampleDt < simulation.duration) {
    const std::optional<RunSample> atDuration = run.sampleAt(simulation.duration);
    if (atDuration && observe) observe(simulation.duration, *atDuration, false);
  }
  result.stoppedBy = run.stoppedBy();
  if (result.stoppedBy && !simulation.model.friction.cone) {
    noteFrictionNeeded(result.frictionNeeded, result.stoppedBy->t, result.stoppedBy->forward);
  }
  const bool flat = result.stoppedBy && (result.stoppedBy->event == physics::ModelEvent::CoinFlat ||
                                         result.stoppedBy->event == physics::ModelEvent::FaceDown);
  if (!simulation.model.effects.empty() && flat) {
    // The stop itself is the sample nearest the singularity; the fit needs it most.
    singularTime.add(result.stoppedBy->t, physics::tiltAboveFloor(result.stoppedBy->forward));
    result.singularTime = singularTime.estimate();
  }
  result.warnings = run.warnings();
  result.switches = run.switches();
  result.impacts = run.impacts();
  result.flight = simulation.flight;
  result.stats = run.stats();
  return result;
}

std::vector<std::string> reportLines(const TrajectoryReport& report) {
  // The run's notes in the order the coin met them: a reader follows the motion down the log.
  std::vector<std::pair<double, std::string>> timed;
  for (const ModeSwitch& w : report.switches) {
    timed.emplace_back(w.t, fmt::format("coinroll: {} at t = {:.9f} s", w.toSliding ? "slides" : "rolls", w.t));
  }
  for (const ImpactRecord& impact : report.impacts) {
    timed.emplace_back(
        impact.t,
        fmt::format("coinroll: impact at t = {:.9f}, normal speed {:.6g} m/s ({}{})", impact.t, impact.normalSpeed,
                    impact.corner ? "the other corner, at upright; " : "",
                    impact.bouncesEnd
                        ? fmt::format("bounce-end: the rim stays on the floor, {:.3g} J lost", impact.energyLost)
                        : fmt::format("rebound {:.6g} m/s, {:.3g} J lost", impact.reboundSpeed, impact.energyLost)));
  }
  for (const RunEvent& warning : report.warnings) {
    timed.emplace_back(warning.t, "coinroll: warning: the ideal contact fails here (on_invalid: warn, going on): " +
                                      describeStop(warning));
  }
  std::stable_sort(timed.begin(), timed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> lines;
  for (auto& [t, line] : timed) lines.push_back(std::move(line));
  if (report.stoppedBy) lines.push_back("coinroll: stopped early: " + describeStop(*report.stoppedBy));
  using physics::ModelEvent;
  if (report.flight && report.stoppedBy &&
      (report.stoppedBy->event == ModelEvent::Rest || report.stoppedBy->event == ModelEvent::FaceDown ||
       report.stoppedBy->event == ModelEvent::CoinFlat || report.stoppedBy->event == ModelEvent::Decided)) {
    const physics::FaceUp face = physics::faceUp(report.stoppedBy->state.theta);
    lines.push_back(fmt::format("coinroll: {} (the {} face up)", physics::faceName(face),
                                face == physics::FaceUp::Heads ? "+e_Z" : "-e_Z"));
  }
  if (report.stoppedBy && report.stoppedBy->event == ModelEvent::OnEdge) {
    lines.push_back("coinroll: on its edge (neither face up)");
  }
  if (report.singularTime) {
    const SingularTimeEstimate& e = *report.singularTime;
    lines.push_back(
        fmt::format("coinroll: singular time t0 = {:.6f} s, {:.3g} s after the stop "
                    "(tilt ~ (t0 - t)^{:.3f}, fitted over {:.6g} s <= t <= {:.6g} s, {} samples)",
                    e.t0, e.t0 - report.stoppedBy->t, e.gamma, e.fitFrom, e.fitTo, e.samples));
  }
  if (const std::optional<FrictionNeeded>& needed = report.frictionNeeded) {
    // Below 1e-9 it is round-off of a reaction that needs none (spin in place, straight rolling).
    lines.push_back(needed->ratio < 1e-9
                        ? fmt::format("coinroll: no friction cone (the scene has no `friction`): rolling needed no "
                                      "friction (|F|/N at most {:.3g} over the samples)",
                                      needed->ratio)
                        : fmt::format("coinroll: no friction cone (the scene has no `friction`): rolling needed |F|/N "
                                      "up to {:.6g}, at t = {:.6f} s (largest over the samples); a friction "
                                      "coefficient below it would have let the coin slip",
                                      needed->ratio, needed->t));
  }
  lines.push_back(fmt::format("coinroll: {} rows, {} steps ({} rejected), {} right-hand-side evaluations", report.rows,
                              report.stats.acceptedSteps, report.stats.rejectedSteps, report.stats.rhsEvaluations));
  return lines;
}

}  // namespace coinroll::pipeline
