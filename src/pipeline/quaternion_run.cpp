// The quaternion formulation's runs, with and without the dissipated energy: their integrator is
// compiled here alone (formulation_run.h). HybridRun's rolling segments compile their own.
#include "pipeline/formulation_run.h"

namespace coinroll::pipeline {

template std::unique_ptr<Motion> startFormulationRun<physics::Formulation::Quaternion>(const Simulation&);

}  // namespace coinroll::pipeline
