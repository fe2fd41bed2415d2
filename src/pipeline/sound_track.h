#pragma once
// A render's sound track, made with its pictures (docs/sound.md).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "pipeline/coin_sound.h"
#include "scene/scene_config.h"
#include "video/frame_sink.h"

namespace coinroll::pipeline {

// The sound track, produced frame by frame from the states the pictures use: the block between
// frames k - 1 and k is synthesised when frame k's state is known, its pitch moving linearly
// between the two frames' (docs/sound.md §2).
class SoundTrack {
 public:
  // `impactScale`: the energy an impact must take to knock at full volume, J.
  SoundTrack(const scene::AudioSpec& spec, int fps, double impactScale)
      : spec_(spec), fps_(fps), synth_(spec, video::kAudioSampleRate), impactScale_(impactScale) {}

  // An impact between the previous frame and the next one, at `fraction` of the way: it knocks in
  // the next block, its loudness the square root of its energy over impactScale, capped at 1.
  void knock(double fraction, double energyLost) { knocks_.push_back({fraction, energyLost}); }

  // Each call's block of sound ends at frame k; it goes to `sink`, or nowhere when that is null (a
  // frame outside the window), still synthesised so the sound is the full render's.
  // `landing`: frame k is the coin's landing, where the sound fades out to the silence of the hold.
  // `precessionRate`: phi-dot at frame k, rad/s.
  void reachFrame(long k, double precessionRate, double playbackRate, video::FrameSink* sink, bool landing) {
    // Omega = |phi-dot|, the contact point's rate round the floor; with pitch "video" the sound is
    // played at the picture's speed, so its frequency scales with simulated seconds per video second.
    const double rate = spec_.pitch == scene::AudioSpec::Pitch::Video ? playbackRate : 1.0;
    const double f = spec_.frequencyScale * std::abs(precessionRate) / (2 * std::numbers::pi) * rate;
    if (k > 0) emit(k, f, sink, landing);
    frequency_ = f;
  }

  // The block up to frame k of a coin lying still: silence.
  void rest(long k, video::FrameSink* sink) {
    block_.assign(static_cast<std::size_t>(sampleAt(k) - sampleAt(k - 1)), 0.0f);
    if (sink != nullptr) sink->pushAudio(block_);
  }

  // The last frame's block, so the track lasts exactly as long as the video.
  void finish(long frames, video::FrameSink* sink, bool resting) {
    if (resting)
      rest(frames, sink);
    else
      emit(frames, frequency_, sink, true);
  }

 private:
  // Sample index at which frame k starts: k * rate / fps, exact in integers.
  std::int64_t sampleAt(long k) const { return static_cast<std::int64_t>(k) * video::kAudioSampleRate / fps_; }

  void emit(long k, double f, video::FrameSink* sink, bool last) {
    block_.clear();
    synth_.synthesize(frequency_, f, static_cast<std::size_t>(sampleAt(k) - sampleAt(k - 1)), block_);
    synth_.ringOn(block_);
    for (const auto& [fraction, energy] : knocks_) {
      const auto at = static_cast<std::size_t>(fraction * static_cast<double>(block_.size()));
      synth_.addImpact(block_, std::min(at, block_.size()), std::sqrt(energy / impactScale_));
    }
    knocks_.clear();
    if (k == 1) synth_.fadeIn(block_);
    if (last) synth_.fadeOut(block_);
    if (sink != nullptr) sink->pushAudio(block_);
  }

  scene::AudioSpec spec_;
  int fps_;
  CoinSound synth_;
  double frequency_ = 0;  // Hz, at the previous frame
  std::vector<float> block_;
  double impactScale_;
  std::vector<std::pair<double, double>> knocks_;  // the next block's impacts: fraction of it, J
};

}  // namespace coinroll::pipeline
