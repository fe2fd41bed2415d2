#pragma once
// The trajectory CSV of docs/contract.md §3: the header, then one row per sample of
// sampleTrajectory, every number with 17 significant digits (each double round-trips).

#include <ostream>

#include "pipeline/simulation.h"
#include "pipeline/trajectory_samples.h"

namespace coinroll::pipeline {

// Integrates `simulation` and writes the header and one row per sample time to `out`.
TrajectoryReport writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out);

}  // namespace coinroll::pipeline
