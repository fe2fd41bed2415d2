#pragma once
// What an EncoderSink is built with: the container and codec, frame size and rate, the x264 settings,
// alpha, an audio track or not, and the provenance written into the file.
// Plain data, std and image/picture_size.h only, so src/scene can hold these options (and validate a scene file into
// them) without seeing libav: the one definition of each default and limit.

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "image/picture_size.h"

namespace coinroll::video {

// x264's own preset names (x264_preset_names), fastest first. Checked before the encoder opens,
// so a typo is reported by name instead of as libx264's generic "Invalid argument".
inline constexpr std::array<std::string_view, 10> kX264Presets = {
    "ultrafast", "superfast", "veryfast", "faster", "fast", "medium", "slow", "slower", "veryslow", "placebo"};
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

// The video kinds coinroll writes: each kind's row in video_kinds.cpp says what it is made of
// and what it can carry (docs/outputs.md "Video formats").
enum class VideoFormat { Mp4, Gif, WebM, Mov };

// What says who made a file (docs/outputs.md "Provenance"): the program and its release, and a
// digest of the scene it rendered. No date and no git revision, so the same release and scene give
// the same bytes. Empty: the file says nothing of its origin (render.provenance: false).
struct Provenance {
  std::string software;     // "coinroll 0.1.0"
  std::string sceneDigest;  // "fnv1a64:0123456789abcdef"

  bool empty() const { return software.empty(); }
  // "coinroll 0.1.0, scene fnv1a64:0123456789abcdef": one line for a Comment tag.
  std::string comment() const { return software + ", scene " + sceneDigest; }
  // Key and value pairs for PNG tEXt chunks: Software, coinroll-scene-digest and Comment.
  std::vector<std::pair<std::string, std::string>> pngText() const {
    if (empty()) return {};
    return {{"Software", software}, {"coinroll-scene-digest", sceneDigest}, {"Comment", comment()}};
  }
};

struct VideoOptions {
  VideoFormat format = VideoFormat::Mp4;      // also the kind of a name without an extension to go by (/dev/stdout)
  int width = image::kDefaultPictureWidth;    // pixels, even (4:2:0 chroma is subsampled by 2 each way)
  int height = image::kDefaultPictureHeight;  // pixels, even
  int fps = 30;  // frames per second, > 0 and within the kind's maxFps; timestamps are frame index / fps
  X264Options x264;
  // Adds a mono AAC track (FFmpeg's own encoder, 48 kHz, 128 kbit/s) fed by pushAudio(), in the
  // kinds that hold audio (validate() refuses it for the others).
  bool audio = false;
  // Keeps the frames' alpha (the kinds with an alpha pixel format; validate() refuses it for the others).
  bool alpha = false;
  Provenance provenance;
};

}  // namespace coinroll::video
