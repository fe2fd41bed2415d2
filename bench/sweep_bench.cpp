// Sweep throughput: a 100 x 100 grid (tilt 5..40 deg, spin 4..16 rad/s) of 5 s toy-coin runs
// (radius 3.75 cm, 0.4 kg, DOP853 at the default tolerances), swept in-process by
// pipeline::runSweep into a discarding stream, on 1 and 2 threads in the same run. Prints points
// per second, the speed-up and the time for the whole 10 000-point grid. The speed-up is measured on
// the same 2000-point subgrid (every fifth tilt) on both thread counts, so both see the same mix
// of cheap and dear points.
// Run: build/bench/sweep_bench
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <ostream>
#include <streambuf>
#include <thread>

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
  NullBuffer buffer;
  std::ostream out(&buffer);
  const auto start = std::chrono::steady_clock::now();
  const pipeline::SweepResult result = pipeline::writeSweepCsv(spec, out, {}, nullptr);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (result.failed != 0) std::abort();
  return seconds;
}

}  // namespace

int main() {
  pipeline::SweepSpec spec;
  spec.scene = {{"coin", {{"shape", "disk"}, {"radius", 0.0375}, {"mass", 0.4}}},
                {"initial", {{"theta", 10}, {"omega_Z", 12}}},
                {"duration", 5}};
  spec.sourceName = "sweep_bench";
  spec.axes = {pipeline::parseGridAxis("initial.theta=5:40:100"), pipeline::parseGridAxis("initial.omega_Z=4:16:100")};

  const double one = sweepSeconds(spec, 1, 20), two = sweepSeconds(spec, 2, 20);
  const double grid = sweepSeconds(spec, 2, 100);
  fmt::print("hardware threads: {}\n", std::thread::hardware_concurrency());
  fmt::print("{:<28} {:>8} {:>10} {:>12}\n", "run", "points", "seconds", "points/s");
  fmt::print("{:<28} {:>8} {:>10.2f} {:>12.0f}\n", "subgrid, 1 thread", 2000, one, 2000 / one);
  fmt::print("{:<28} {:>8} {:>10.2f} {:>12.0f}\n", "subgrid, 2 threads", 2000, two, 2000 / two);
  fmt::print("{:<28} {:>8} {:>10.2f} {:>12.0f}\n", "whole grid, 2 threads", 10000, grid, 10000 / grid);
  fmt::print("speed-up 2 vs 1 thread: {:.2f}; 10 000-point grid on 2 threads: {:.1f} s\n", one / two, grid);
}
