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

// The video kinds coinroll writes (docs/outputs.md "Video formats"): the container, its codec and
// pixel format follow from the kind.
enum class VideoFormat {
  Mp4,   // H.264 (libx264), yuv420p, BT.709 limited range; AAC when there is audio
  Gif,   // GIF (FFmpeg's encoder), a fixed 252-colour palette with ordered dithering, looping
  WebM,  // VP9 (libvpx-vp9), yuv420p, or yuva420p with alpha
  Mov,   // ProRes 4444 (prores_ks), yuv444p10le, or yuva444p10le with alpha; AAC when there is audio
};
// Every kind, in the order of the enum: the one list an output name is matched against.
inline constexpr std::array<VideoFormat, 4> kVideoFormats = {VideoFormat::Mp4, VideoFormat::Gif, VideoFormat::WebM,
                                                             VideoFormat::Mov};

// ".mp4", ".gif", ".webm" or ".mov", the extension a file of `format` is chosen by.
constexpr std::string_view extensionOf(VideoFormat format) {
  switch (format) {
    case VideoFormat::Mp4: return ".mp4";
    case VideoFormat::Gif: return ".gif";
    case VideoFormat::WebM: return ".webm";
    case VideoFormat::Mov: return ".mov";
  }
  return {};
}
// Whether a file of `format` keeps the frames' alpha (VideoOptions::alpha).
constexpr bool keepsAlpha(VideoFormat format) { return format == VideoFormat::WebM || format == VideoFormat::Mov; }
// Whether a file of `format` can hold a sound track (VideoOptions::audio).
constexpr bool holdsAudio(VideoFormat format) { return format == VideoFormat::Mp4 || format == VideoFormat::Mov; }

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
  VideoFormat format = VideoFormat::Mp4;
  int width = image::kDefaultPictureWidth;    // pixels, even (4:2:0 chroma is subsampled by 2 each way)
  int height = image::kDefaultPictureHeight;  // pixels, even
  int fps = 30;      // frames per second, > 0; timestamps are frame index / fps
  X264Options x264;
  // Adds a mono AAC track (FFmpeg's own encoder, 48 kHz, 128 kbit/s) fed by pushAudio().
  bool audio = false;
  // Keeps the frames' alpha (WebM and MOV only; validate() refuses it for the others).
  bool alpha = false;
  Provenance provenance;
};


}  // namespace coinroll::video
