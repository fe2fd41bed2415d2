#include "pipeline/singular_time.h"

#include <cmath>
#include <span>

namespace coinroll::pipeline {

namespace {

struct PowerLaw {
  double exponent = 0;         // n
  double squaredResidual = 0;  // sum of (ln alpha - fit)^2
};

// Least squares ln alpha = ln c + n ln(t0 - t) for a given t0, about the means so the sums stay well
// conditioned; the residual summed term by term, not as Syy - Sxy^2 / Sxx, whose cancellation would
// blur the minimum over t0 at 1e-8 instead of round-off.
PowerLaw fitAt(std::span<const double> t, std::span<const double> logAlpha, double t0) {
  const auto count = static_cast<double>(t.size());
  double meanX = 0, meanY = 0;
  for (std::size_t i = 0; i < t.size(); ++i) meanX += std::log(t0 - t[i]), meanY += logAlpha[i];
  meanX /= count, meanY /= count;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double dx = std::log(t0 - t[i]) - meanX;
    sxx += dx * dx;
    sxy += dx * (logAlpha[i] - meanY);
  }
  PowerLaw law{.exponent = sxy / sxx};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double r = logAlpha[i] - meanY - law.exponent * (std::log(t0 - t[i]) - meanX);
    law.squaredResidual += r * r;
  }
  return law;
}

}  // namespace

void SingularTimeFit::add(double t, double alpha) { samples_.push_back({t, alpha}); }

std::optional<SingularTimeEstimate> SingularTimeFit::estimate() const {
  // A thin coin's stop sample lies on the floor up to the event location's round-off.
  const double floor = floor_ * (1 - 1e-9);
  std::size_t end = samples_.size();
  while (end > 0 && !(samples_[end - 1].alpha >= floor)) --end;
  if (end == 0) return std::nullopt;
  const double ceiling = kTiltSpan * samples_[end - 1].alpha;
  std::size_t first = end - 1;
  while (first > 0 && samples_[first - 1].alpha >= floor && samples_[first - 1].alpha <= ceiling) --first;
  const auto count = static_cast<int>(end - first);
  if (count < kMinimumSamples) return std::nullopt;

  std::vector<double> t, logAlpha;
  for (std::size_t i = first; i < end; ++i) t.push_back(samples_[i].t), logAlpha.push_back(std::log(samples_[i].alpha));
  // t0 by golden-section search on x = ln(t0 - t_last), from a millionth of the window's length to a
  // thousand lengths after it: a fit that wants t0 further off sees an exponential, not a singularity.
  const double last = t.back(), span = last - t.front();
  const double lowest = std::log(1e-6 * span), highest = std::log(1e3 * span);
  const auto residual = [&](double x) { return fitAt(t, logAlpha, last + std::exp(x)).squaredResidual; };
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double lo = lowest, hi = highest;
  for (int k = 0; k < 100; ++k) {  // 100 shrinks by 0.618 take the bracket's 21 units below round-off
    const double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    if (residual(x1) < residual(x2)) {
      hi = x2;
    } else {
      lo = x1;
    }
  }
  const double x = (lo + hi) / 2;
  if (highest - x < 1e-3 * (highest - lowest)) return std::nullopt;  // no singularity within reach
  const double t0 = last + std::exp(x);
  const PowerLaw law = fitAt(t, logAlpha, t0);
  if (!(law.exponent > 0)) return std::nullopt;  // the tilt must fall towards t0
  return SingularTimeEstimate{.t0 = t0, .gamma = law.exponent, .fitFrom = t.front(), .fitTo = last, .samples = count};
}

}  // namespace coinroll::pipeline
