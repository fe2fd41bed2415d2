// The C++ side of bench/python_overhead.py, loaded into the benchmark's Python process with
// ctypes so that C++ and Python calls alternate one by one on the same machine state (a separate
// process drifted by 10 % against the Python side on the loaded machine).
#include <coinroll/coinroll.h>

#include <chrono>
#include <exception>

// Seconds coinroll::simulate takes on the scene file, the scene loaded outside the timing;
// -1 if it throws.
extern "C" __attribute__((visibility("default"))) double coinroll_simulate_seconds(const char* sceneFile,
                                                                                   double sampleDt) {
  try {
    const coinroll::Scene scene = coinroll::Scene::fromFile(sceneFile);
    const auto start = std::chrono::steady_clock::now();
    const coinroll::Columns columns = coinroll::simulate(scene, sampleDt);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const std::exception&) {
    return -1;
  }
}
