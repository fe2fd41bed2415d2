// The native side of bench/wasm_vs_native.js: the calls `coinroll simulate` makes for its CSV
// (cli/commands.cpp runSimulate), scene text to CSV text in memory, timed in this process, so that
// the WebAssembly core is set against the same work without the program's start (loading its
// rendering and video libraries takes tens of milliseconds, more than the default scene's run).
// Prints the wall and CPU seconds of one run and the rows.
// Run: build/bench/csv_run_timer [SCENE.json]
#include <fmt/format.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/simulation.h"
#include "pipeline/trajectory_csv.h"
#include "scene/scene_loader.h"

int main(int argc, char** argv) try {
  using namespace coinroll;
  std::string text;
  if (argc > 1) {
    std::ifstream file(argv[1], std::ios::binary);
    if (!file) throw std::runtime_error(fmt::format("{}: cannot open the scene file", argv[1]));
    text.assign(std::istreambuf_iterator<char>(file), {});
  }
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  const char* name = argc > 1 ? argv[1] : "built-in default scene";
  const nlohmann::json document = argc > 1 ? scene::parseSceneText(text, name) : scene::builtInDefaultScene();
  const pipeline::Simulation simulation = pipeline::buildSimulation(scene::parseScene(document, name));
  std::ostringstream csv;
  const pipeline::TrajectoryReport result = pipeline::writeTrajectoryCsv(simulation, 0.01, csv);
  const double cpu = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  fmt::print("{:.9f} {:.9f} {}\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), cpu,
             result.rows);
} catch (const std::exception& e) {
  fmt::print(stderr, "csv_run_timer: {}\n", e.what());
  return 1;
}
