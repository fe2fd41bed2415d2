#pragma once
// The trajectory CSV of INTERFACE.md: fixed header, rows at t = k S from the dense output.

#include <optional>
#include <ostream>
#include <vector>

#include "integrate/events.h"
#include "physics/coin_state.h"
#include "pipeline/hybrid_run.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"
#include "pipeline/singular_time.h"

namespace coinroll::pipeline {

inline constexpr const char* kCsvHeader =
    "t,theta,phi,psi,omega_X,omega_Y,omega_Z,x,y,z,contact_x,contact_z,energy,normal_force,friction_force";

// Appended to the header when the scene has effects: power dissipated now (W) and since t = 0 (J).
inline constexpr const char* kCsvDissipationColumns = ",power,dissipated";
// With "sliding": true (after power and dissipated, which then include friction's work).
inline constexpr const char* kCsvSlidingColumns = ",slip_speed,sliding";

// Number of rows for a duration and sample step: k = 0 .. floor(duration / S). The quotient is
// nudged by a relative 1e-9 so a duration that is a whole number of steps keeps its last row
// despite round-off: 2.3 / 0.01 is 229.99999999999997 in binary, which alone would give 230 rows
// instead of 231.
long sampleCount(double duration, double sampleDt);

struct CsvRunResult {
  long rows = 0;
  std::optional<RunEvent> stoppedBy;
  std::vector<RunEvent> warnings;  // on_invalid "warn": crossings gone past
  std::vector<ModeSwitch> switches;  // "sliding": true: each switch between rolling and sliding
  std::optional<SingularTimeEstimate> singularTime;  // a spin-down that reached coin-flat or face-down
  integrate::Stats stats;
};

// Integrates `simulation` and writes the header and one row per sample time to `out`.
CsvRunResult writeTrajectoryCsv(const Simulation& simulation, double sampleDt, std::ostream& out);

}  // namespace coinroll::pipeline
