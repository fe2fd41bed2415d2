// Sweep throughput: a 100 x 100 grid (tilt 5..40 deg, spin 4..16 rad/s) of 5 s toy-coin runs
// (radius 3.75 cm, 0.4 kg, DOP853 at the default tolerances), swept in-process by
// pipeline::runSweep into a discarding stream, on 1 and 2 threads in the same run. Prints points
// per second, the speed-up and the time for the whole 10 000-point grid.
// Run: build/bench/sweep_bench [POINTS_FOR_ONE_THREAD]   (default 2000: the one-thread rate is
// measured on the first 2000 points, a fifth of the grid, to keep the bench short)
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <ostream>
#include <streambuf>
#include <thread>

#include "integrate/solver_config.h"
#include "pipeline/sweep.h"

namespace {

using namespace coinroll;

class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

double sweepSeconds(pipeline::SweepSpec spec, int threads, long thetaCount) {
  spec.threads = threads;
  spec.axes[0].count = thetaCount;
  spec.axes[0].stop = spec.axes[0].start + (40.0 - 5.0) * static_cast<double>(thetaCount - 1) / 99.0;
  NullBuffer buffer;
  std::ostream out(&buffer);
  const auto start = std::chrono::steady_clock::now();
  const pipeline::SweepResult result = pipeline::runSweep(spec, out, {}, nullptr);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (result.failed != 0) std::abort();
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  const long onePoints = argc > 1 ? std::atol(argv[1]) : 2000;
  pipeline::SweepSpec spec;
  spec.scene = {{"coin", {{"shape", "disk"}, {"radius", 0.0375}, {"mass", 0.4}}},
                {"initial", {{"theta", 10}, {"omega_Z", 12}}},
                {"duration", 5}};
  spec.sourceName = "sweep_bench";
  spec.parseOptions = {.solverMethods = integrate::methodNames()};
  spec.axes = {pipeline::parseGridAxis("initial.theta=5:40:100"), pipeline::parseGridAxis("initial.omega_Z=4:16:100")};

  const long thetaRows = onePoints / 100;
  const double one = sweepSeconds(spec, 1, thetaRows);
  const double two = sweepSeconds(spec, 2, 100);
  const double oneRate = static_cast<double>(thetaRows * 100) / one, twoRate = 10000.0 / two;
  fmt::print("hardware threads: {}\n", std::thread::hardware_concurrency());
  fmt::print("{:<10} {:>8} {:>10} {:>12}\n", "threads", "points", "seconds", "points/s");
  fmt::print("{:<10} {:>8} {:>10.2f} {:>12.0f}\n", 1, thetaRows * 100, one, oneRate);
  fmt::print("{:<10} {:>8} {:>10.2f} {:>12.0f}\n", 2, 10000, two, twoRate);
  fmt::print("speed-up 2 vs 1 thread: {:.2f}; 10 000-point grid on 2 threads: {:.1f} s\n", twoRate / oneRate, two);
}
