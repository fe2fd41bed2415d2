#include "pipeline/singular_time.h"

#include <cmath>

namespace coinroll::pipeline {

void SingularTimeFit::add(double t, double energy, double power) {
  if (power > 0 && energy > 0) samples_.push_back({t, energy / power});
}

std::optional<SingularTimeEstimate> SingularTimeFit::estimate() const {
  if (samples_.empty()) return std::nullopt;
  // u is (t0 - t) / gamma: a decade of u is a decade of t0 - t.
  const double uLast = samples_.back().u;
  std::size_t first = samples_.size();
  while (first > 0 && samples_[first - 1].u <= uLast * std::pow(10.0, kDecades)) --first;
  const auto count = static_cast<int>(samples_.size() - first);
  if (count < kMinimumSamples) return std::nullopt;
  // Least squares u = c0 + c1 t, about the window's mean time so the sums stay well conditioned.
  double meanT = 0, meanU = 0;
  for (std::size_t i = first; i < samples_.size(); ++i) meanT += samples_[i].t, meanU += samples_[i].u;
  meanT /= count, meanU /= count;
  double stt = 0, stu = 0;
  for (std::size_t i = first; i < samples_.size(); ++i) {
    const double dt = samples_[i].t - meanT;
    stt += dt * dt;
    stu += dt * (samples_[i].u - meanU);
  }
  const double slope = stu / stt;
  if (!(slope < 0)) return std::nullopt;  // u must shrink towards the singularity
  return SingularTimeEstimate{
      .t0 = meanT - meanU / slope, .gamma = -1 / slope, .fitFrom = samples_[first].t, .samples = count};
}

}  // namespace coinroll::pipeline
