#pragma once
// The singular time t0 of a spin-down, estimated from the motion without knowing which law
// dissipates (docs/euler_disk.md §4): near flat the tilt above the floor goes as
// alpha ~ c (t0 - t)^n, so a least-squares fit of ln alpha against ln(t0 - t), over t0 as well,
// gives t0 and n. The tilt, not the energy: a thick coin's energy tends to M g h / 2 and, held to
// rolling, keeps the face spin the constraint pumped up, so E - E_rest is no power of t0 - t there.

#include <numbers>
#include <optional>
#include <vector>

namespace coinroll::pipeline {

struct SingularTimeEstimate {
  double t0 = 0;       // s
  double gamma = 0;    // the tilt's exponent n: alpha ~ (t0 - t)^n (1/3 Moffatt, 4/9 boundary layer, 2/3 rolling)
  double fitFrom = 0;  // s, first sample of the fitted window
  double fitTo = 0;    // s, last sample of the fitted window
  int samples = 0;     // samples in the window
};

class SingularTimeFit {
 public:
  // floor: the least tilt (rad) the fit takes, kQuasiSteadyFloor unless a caller knows the quasi-steady
  // state lasts further (the tests' quaternion runs check it does, docs/euler_disk.md §5).
  explicit SingularTimeFit(double floor = kQuasiSteadyFloor) : floor_(floor) {}

  // One sample of the run: time (s) and tilt above the floor alpha (rad), in time order.
  void add(double t, double alpha);

  // The fit over the run's last stretch of samples with floor <= alpha <= kTiltSpan times
  // the least alpha there; std::nullopt with fewer than kMinimumSamples, or when no power law with
  // n > 0 and t0 after the window fits (a tilt that does not fall to zero ahead, e.g. spin friction's
  // alpha ~ t^-2, docs/euler_disk.md (3.8)).
  std::optional<SingularTimeEstimate> estimate() const;

  // rad, 0.5 degrees: below it the air couples damp the rocking faster than the coin precesses and
  // the quasi-steady state the exponents belong to ends (docs/euler_disk.md §5, docs/rim.md §7); a
  // thin coin's spin-down stops there (physics::kSpinDownFlatTilt), a thick coin's goes on to 0.05.
  static constexpr double kQuasiSteadyFloor = 0.5 * std::numbers::pi / 180;
  // A factor 3 in alpha is 0.7 to 1.1 decades of t0 - t for n from 2/3 to 4/9: about the one decade
  // over which a single law's exponent holds where two share the dissipation (docs/euler_disk.md (3.12)).
  static constexpr double kTiltSpan = 3;
  static constexpr int kMinimumSamples = 8;

 private:
  struct Sample {
    double t, alpha;  // s, rad
  };
  double floor_;
  std::vector<Sample> samples_;
};

}  // namespace coinroll::pipeline
