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
