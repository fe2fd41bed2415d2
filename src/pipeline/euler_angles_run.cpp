// The Euler angles' runs, with and without the dissipated energy: their integrator is compiled here
// alone (formulation_run.h).
#include "pipeline/formulation_run.h"

namespace coinroll::pipeline {

template std::unique_ptr<Motion> startFormulationRun<physics::Formulation::EulerAngles>(const Simulation&);

}  // namespace coinroll::pipeline
