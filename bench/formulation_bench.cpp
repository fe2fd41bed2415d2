// Accuracy per unit of time of the two formulations on every examples/*.json scene: each run is
// sampled every 0.01 s like `simulate`, its error is the largest difference from a reference run
// (Euler angles, rtol 1e-13) over the samples (angles in rad, rates in sqrt(g/a), positions in
// a), its cost the best of three wall times. Prints one row per scene, formulation and rtol.
// Run: build/bench/formulation_bench
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "pipeline/coin_run.h"
#include "pipeline/simulation.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

std::vector<physics::StateVec> samples(const pipeline::Simulation& simulation) {
  pipeline::CoinRun run(simulation);
  std::vector<physics::StateVec> result;
  for (int k = 0; k * 0.01 <= simulation.duration + 1e-12; ++k) {
    const std::optional<physics::CoinState> s = run.stateAt(k * 0.01);
    if (!s) break;
    result.push_back(physics::toVector(*s));
  }
  return result;
}

double largestError(const pipeline::Simulation& simulation, const std::vector<physics::StateVec>& run,
                    const std::vector<physics::StateVec>& reference) {
  const double rate = physics::naturalRate(simulation.model), a = simulation.model.a;
  const physics::StateVec scale = (physics::StateVec() << 1, 1, 1, rate, rate, rate, a, a).finished();
  double worst = 0;
  for (std::size_t k = 0; k < std::min(run.size(), reference.size()); ++k) {
    worst = std::max(worst, (run[k] - reference[k]).cwiseQuotient(scale).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

int main() {
  std::vector<std::filesystem::path> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(COINROLL_SOURCE_DIR "/examples"))
    scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  fmt::print("{:<18} {:<13} {:>6} {:>10} {:>10} {:>9}\n", "scene", "formulation", "rtol", "rhs evals", "time ms",
             "error");
  for (const auto& file : scenes) {
    pipeline::Simulation simulation = pipeline::buildSimulation(scene::loadScene(file, {}));
    simulation.formulation = scene::Formulation::EulerAngles;
    simulation.solver.rtol = 1e-13;
    simulation.solver.atol = 1e-15;
    const std::vector<physics::StateVec> reference = samples(simulation);
    if (static_cast<double>(reference.size() - 1) * 0.01 < simulation.duration - 0.01) {
      fmt::print("{:<18} skipped: the Euler-angle reference stops with coin-flat\n", file.stem().string());
      continue;
    }
    for (const scene::Formulation formulation : {scene::Formulation::EulerAngles, scene::Formulation::Quaternion}) {
      for (const double rtol : {1e-6, 1e-8, 1e-10, 1e-12}) {
        simulation.formulation = formulation;
        simulation.solver.rtol = rtol;
        simulation.solver.atol = rtol * 1e-2;
        double best = INFINITY;
        std::vector<physics::StateVec> run;
        for (int repeat = 0; repeat < 3; ++repeat) {
          const auto start = std::chrono::steady_clock::now();
          run = samples(simulation);
          best = std::min(best,
                          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        pipeline::CoinRun counter(simulation);
        counter.stateAt(simulation.duration);
        fmt::print("{:<18} {:<13} {:>6.0e} {:>10} {:>10.3f} {:>9.1e}\n", file.stem().string(),
                   formulation == scene::Formulation::EulerAngles ? "euler-angles" : "quaternion", rtol,
                   counter.stats().rhsEvaluations, best, largestError(simulation, run, reference));
      }
    }
  }
}
