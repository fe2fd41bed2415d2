#pragma once
// What an Mp4Sink is built with: frame size and rate, the x264 settings, an audio track or not.
// Plain data and std only, so src/scene can hold these options (and validate a scene file into
// them) without seeing libav: the one definition of each default and limit.

#include <array>
#include <string>
#include <string_view>

namespace coinroll::video {

// x264's own preset names (x264_preset_names), fastest first. Checked before the encoder opens,
// so a typo is reported by name instead of as libx264's generic "Invalid argument".
inline constexpr std::array<std::string_view, 10> kX264Presets = {"ultrafast", "superfast", "veryfast", "faster", "fast",
                                                                  "medium",    "slow",      "slower",   "veryslow", "placebo"};
inline constexpr int kMaxCrf = 51;          // x264's constant rate factor runs 0 (lossless) .. 51
inline constexpr int kMaxX264Threads = 16;  // a bound on typos (x264 itself allows 128); see X264Options::threads

struct X264Options {
  int crf = 18;                     // constant rate factor, 0 (lossless) .. kMaxCrf; lower is better
  std::string preset = "veryfast";  // one of kX264Presets
  // Encoder threads, 1..kMaxX264Threads. Fixed, never "auto": x264's output depends on its thread
  // count, so a count taken from the machine would make the same render differ between machines.
  // One: the renderer already keeps both cores of the reference machine busy, and a second
  // encoder thread only competes with it (bench/pipeline_bench: 8.85 s vs 9.04 s end to end for
  // the orbiting 10 s clip).
  int threads = 1;
};

struct Mp4Options {
  int width = 1280;  // pixels, even (4:2:0 chroma is subsampled by 2 each way)
  int height = 720;  // pixels, even
  int fps = 30;      // frames per second, > 0; timestamps are frame index / fps
  X264Options x264;
  // Adds a mono AAC track (FFmpeg's own encoder, 48 kHz, 128 kbit/s) fed by pushAudio().
  bool audio = false;
};

}  // namespace coinroll::video
