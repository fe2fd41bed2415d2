#pragma once
// The singular time t0 of a spin-down, estimated from the motion without knowing which law
// dissipates (docs/euler_disk.md §4): if E ~ (t0 - t)^gamma then u = E / P = (t0 - t) / gamma is
// linear in t, so a least-squares line through u(t) over the last decade gives t0 (its root) and
// gamma (minus the inverse slope).

#include <optional>
#include <vector>

namespace coinroll::pipeline {

struct SingularTimeEstimate {
  double t0 = 0;         // s
  double gamma = 0;      // E ~ (t0 - t)^gamma; in the quasi-steady state alpha has the same exponent
  double fitFrom = 0;    // s, first sample of the fitted window
  int samples = 0;       // samples in the window
};

class SingularTimeFit {
 public:
  // One sample of the run: time (s), energy (J), dissipated power (W).
  void add(double t, double energy, double power);

  // The fit over the samples whose u lies within kDecades of the last one, i.e. the last decade of
  // t0 - t; std::nullopt with fewer than kMinimumSamples there. One decade, not more: where two
  // laws share the dissipation the exponent drifts (docs/euler_disk.md (3.12)), and the toy's
  // two-decade fit lands 0.6 s late against 0.1 s for one decade.
  std::optional<SingularTimeEstimate> estimate() const;

  static constexpr double kDecades = 1;
  static constexpr int kMinimumSamples = 8;

 private:
  struct Sample {
    double t, u;  // s, s
  };
  std::vector<Sample> samples_;
};

}  // namespace coinroll::pipeline
