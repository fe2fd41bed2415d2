#pragma once
// The coin's sound (docs/sound.md): a tone or a train of clicks whose fundamental follows the
// contact point's rate round the floor, f = k Omega / (2 pi), synthesised by integrating the
// phase (so a changing pitch never clicks) and band-limited so nothing folds back below Nyquist.

#include <cstddef>
#include <vector>

#include "scene/scene_config.h"

namespace coinroll::pipeline {

// Hz. The clicks' harmonics stop here: well inside the 24 kHz Nyquist limit of 48 kHz audio and
// above the range where the ear places a buzz's pitch.
inline constexpr double kClickBandLimit = 5000;

// s. Raised-cosine fades at the start and the end of the track, so it neither starts nor stops
// with a step.
inline constexpr double kFadeSeconds = 0.005;

class CoinSound {
 public:
  CoinSound(const scene::AudioSpec& spec, int sampleRate);

  // Appends `count` samples to `out` while the fundamental moves linearly from f0 to f1 (Hz, >= 0).
  void synthesize(double f0, double f1, std::size_t count, std::vector<float>& out);

  // Mixes into `samples` from index `at` the knock of an impact of relative strength `strength` in
  // [0, 1] (docs/sound.md §4): a band-limited ring that dies away in a few milliseconds. What runs past
  // the end of `samples` is kept and mixed into the next call's samples from their start.
  void addImpact(std::vector<float>& samples, std::size_t at, double strength);
  void ringOn(std::vector<float>& samples);

  // Multiplies the first or the last kFadeSeconds of `samples` by a raised-cosine ramp.
  void fadeIn(std::vector<float>& samples) const;
  void fadeOut(std::vector<float>& samples) const;

 private:
  double sample(double f);  // advances the phase by one sample at fundamental f

  scene::AudioSpec spec_;
  int sampleRate_;
  double phase_ = 0;            // cycles, in [0, 1)
  std::vector<float> ringing_;  // the impacts' sound still to come, from the next sample on
};

}  // namespace coinroll::pipeline
