// The cost of a whole spin-down: examples/euler_disk.json run to coin-flat in each formulation and
// with each law alone. Baseline in the same run: the same coin rolling ideally (no effects) from
// the same tilt with a wobble (omega_X = 0.5 rad/s; the steady start alone would take a few
// giant steps) for the toy's spin-down time. Prints wall time (best of five), right-hand-side
// evaluations, steps, the stop time and the energy budget |E + dissipated - E0| / E0 there.
// Run: build/bench/spin_down_bench
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "physics/observables.h"
#include "pipeline/coin_run.h"
#include "pipeline/simulation.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

struct Measurement {
  double seconds = 0;  // wall, best of five
  long evaluations = 0;
  long steps = 0;
  double end = 0;     // s of simulated time
  double budget = 0;  // |E + dissipated - E0| / E0 at the end
};

Measurement measure(const pipeline::Simulation& simulation) {
  Measurement m;
  m.seconds = 1e300;
  for (int repeat = 0; repeat < 5; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
    pipeline::CoinRun run(simulation);
    std::optional<pipeline::RunSample> last = run.sampleAt(0);
    // One query at the end, as a run without samples: the integrator steps to the stop.
    if (const std::optional<pipeline::RunSample> end = run.sampleAt(simulation.duration)) last = end;
    m.seconds = std::min(m.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    m.evaluations = run.stats().rhsEvaluations;
    m.steps = run.stats().acceptedSteps;
    double dissipated = last->dissipated;
    m.end = simulation.duration;
    double endEnergy = last->forward.energy;
    if (const auto hit = run.stoppedBy()) {
      m.end = hit->t;
      endEnergy = hit->forward.energy;
      dissipated = hit->dissipated;
    }
    const double E0 = physics::energy(simulation.model, simulation.initial);
    m.budget = std::abs(endEnergy + dissipated - E0) / E0;
  }
  return m;
}

}  // namespace

int main() {
  const scene::SceneConfig toy = scene::loadScene(std::string(COINROLL_SOURCE_DIR) + "/examples/euler_disk.json", {});

  struct Case {
    std::string name;
    std::vector<std::string> overrides;
  };
  const std::vector<Case> cases = {
      {"toy, Euler angles (the example)", {}},
      {"toy, quaternion", {"solver.formulation=quaternion"}},
      {"boundary-layer air drag only", {R"(effects=[{"type": "air_drag", "model": "boundary_layer"}])"}},
      {"rolling resistance only", {R"(effects=[{"type": "rolling_resistance", "length": 3.75e-6}])"}},
  };
  pipeline::Simulation ideal = pipeline::buildSimulation(toy);
  const Measurement toyRun = measure(pipeline::buildSimulation(toy));
  ideal.model.effects.clear();
  ideal.initial.omega_X = 0.5;
  ideal.duration = toyRun.end;
  const Measurement baseline = measure(ideal);

  fmt::print("{:<36} {:>10} {:>9} {:>10} {:>9} {:>11} {:>9}\n", "case", "sim s", "wall ms", "rhs evals", "steps",
             "budget", "vs ideal");
  fmt::print("{:<36} {:>10.3f} {:>9.1f} {:>10} {:>9} {:>11} {:>9}\n", "ideal rolling, wobbling, same time",
             baseline.end, 1e3 * baseline.seconds, baseline.evaluations, baseline.steps, "-", "1.00");
  for (const Case& c : cases) {
    nlohmann::json document =
        nlohmann::json::parse(std::ifstream(std::string(COINROLL_SOURCE_DIR) + "/examples/euler_disk.json"));
    for (const std::string& o : c.overrides) scene::applyOverride(document, o);
    document["duration"] = 2000;  // every case runs to coin-flat
    const Measurement m = measure(pipeline::buildSimulation(scene::parseScene(document, c.name)));
    fmt::print("{:<36} {:>10.3f} {:>9.1f} {:>10} {:>9} {:>11.2e} {:>9.2f}\n", c.name, m.end, 1e3 * m.seconds,
               m.evaluations, m.steps, m.budget, m.seconds / baseline.seconds);
  }
}
