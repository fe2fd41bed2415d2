#include "pipeline/coin_sound.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace coinroll::pipeline {

CoinSound::CoinSound(const scene::AudioSpec& spec, int sampleRate) : spec_(spec), sampleRate_(sampleRate) {}

double CoinSound::sample(double f) {
  const double x = 2 * std::numbers::pi * phase_;
  double value = 0;
  if (spec_.timbre == scene::AudioSpec::Timbre::Tone) {
    value = std::sin(x);
  } else if (f > 0) {
    // An impulse train band-limited to kClickBandLimit: the harmonics n f up to the limit, all of
    // equal weight, summed in closed form (the Dirichlet kernel), the next harmonic faded in by
    // the fraction of it below the limit so none switches on abruptly as f changes.
    const double harmonics = std::min(kClickBandLimit / f, 1e6);
    const double whole = std::floor(harmonics), fraction = harmonics - whole;
    const double half = std::sin(x / 2);
    const double dirichlet = std::abs(half) < 1e-12 ? whole : std::sin((whole + 0.5) * x) / (2 * half) - 0.5;
    value = (dirichlet + fraction * std::cos((whole + 1) * x)) / harmonics;  // peak 1 at each click
  }
  phase_ += f / sampleRate_;
  phase_ -= std::floor(phase_);
  return spec_.volume * value;
}

void CoinSound::synthesize(double f0, double f1, std::size_t count, std::vector<float>& out) {
  for (std::size_t i = 0; i < count; ++i) {
    const double f = f0 + (f1 - f0) * static_cast<double>(i) / static_cast<double>(count);
    out.push_back(static_cast<float>(sample(f)));
  }
}

namespace {

// The knock of an impact: a sine at kKnockFrequency dying away with time constant kKnockDecay,
// starting from zero so it adds no step. Below kClickBandLimit like the clicks, and long enough to
// be heard as a knock, short enough that a bounce sequence's impacts stay apart.
constexpr double kKnockFrequency = 2500;  // Hz
constexpr double kKnockDecay = 0.004;     // s
constexpr double kKnockLength = 8 * kKnockDecay;

}  // namespace

void CoinSound::addImpact(std::vector<float>& samples, std::size_t at, double strength) {
  const auto length = static_cast<std::size_t>(kKnockLength * sampleRate_);
  if (ringing_.size() < at + length - std::min(at + length, samples.size())) {
    ringing_.resize(at + length - std::min(at + length, samples.size()), 0.0f);
  }
  const double amplitude = spec_.volume * std::clamp(strength, 0.0, 1.0);
  for (std::size_t n = 0; n < length; ++n) {
    const double time = static_cast<double>(n) / sampleRate_;
    const auto value = static_cast<float>(amplitude * std::sin(2 * std::numbers::pi * kKnockFrequency * time) *
                                          std::exp(-time / kKnockDecay));
    const std::size_t i = at + n;
    if (i < samples.size())
      samples[i] += value;
    else
      ringing_[i - samples.size()] += value;
  }
}

void CoinSound::ringOn(std::vector<float>& samples) {
  const std::size_t carried = std::min(ringing_.size(), samples.size());
  for (std::size_t i = 0; i < carried; ++i) samples[i] += ringing_[i];
  ringing_.erase(ringing_.begin(), ringing_.begin() + static_cast<std::ptrdiff_t>(carried));
}

namespace {

void fade(std::vector<float>& samples, int sampleRate, bool in) {
  const auto length = std::min(samples.size(), static_cast<std::size_t>(kFadeSeconds * sampleRate));
  for (std::size_t i = 0; i < length; ++i) {
    const double ramp = 0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(i) / static_cast<double>(length));
    float& s = in ? samples[i] : samples[samples.size() - 1 - i];
    s = static_cast<float>(s * ramp);
  }
}

}  // namespace

void CoinSound::fadeIn(std::vector<float>& samples) const { fade(samples, sampleRate_, true); }
void CoinSound::fadeOut(std::vector<float>& samples) const { fade(samples, sampleRate_, false); }

}  // namespace coinroll::pipeline
