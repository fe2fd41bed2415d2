#pragma once
// Test support: reading back what a sink wrote, stream facts for checks and decoded frames for
// comparisons. The program never reads its outputs back, so this lives beside the tests, not in src/video.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "image/image.h"

namespace coinroll::video {

struct VideoInfo {
  std::string codecName;        // FFmpeg's codec name, e.g. "h264"
  std::string pixelFormat;      // e.g. "yuv420p"
  int width = 0;                // pixels
  int height = 0;               // pixels
  std::int64_t frameCount = 0;  // packets of the video stream (one per frame for H.264 in MP4)
  double durationSeconds = 0;   // s, of the video stream
  double fps = 0;               // frames per second (average frame rate)
  std::string colorPrimaries;   // FFmpeg names: "bt709", or "unknown" when untagged
  std::string colorTransfer;    // e.g. "bt709"
  std::string colorSpace;       // the YUV matrix, e.g. "bt709"
  std::string colorRange;       // "tv" (limited) or "pc" (full)
  bool moovBeforeMdat = false;  // MP4 and MOV top-level boxes: the index precedes the media data
  // The stream carries alpha: its pixel format has it, or (VP9 in WebM, whose alpha travels beside
  // the picture) the container says so (alpha_mode 1).
  bool alpha = false;
  std::map<std::string, std::string> tags;  // the container's metadata, keys as FFmpeg names them
};

// Opens `path` with libavformat and describes its first video stream. Throws std::runtime_error
// naming the path if it cannot be opened or has no video stream.
VideoInfo readVideoInfo(const std::filesystem::path& path);

// Decodes frame `index` (0-based, in presentation order) of the first video stream to RGBA,
// converting with the matrix and range the stream is tagged with (BT.601 when untagged, as
// FFmpeg assumes), alpha included (VP9 through libvpx's decoder, which reads the alpha beside it). Throws
// std::runtime_error naming the path if the file has fewer frames.
image::Image decodeFrame(const std::filesystem::path& path, std::int64_t index);

// Each frame's delay in the GIF at `path`, in hundredths of a second, as its Graphic Control
// Extension holds it: read from the bytes, not through FFmpeg's demuxer, which (as browsers do)
// plays a delay under 2 as 10. Throws std::runtime_error naming the path if it is no GIF89a stream
// or is cut short.
std::vector<int> gifFrameDelays(const std::filesystem::path& path);

// The first audio stream: its codec, rate and duration, and every sample decoded to mono floats
// (the encoder's priming samples, which the container marks to skip, already dropped).
struct DecodedAudio {
  std::string codecName;       // e.g. "aac"
  int sampleRate = 0;          // Hz
  double durationSeconds = 0;  // s, of the audio stream as the container states it
  std::vector<float> samples;  // the first channel
};

// Throws std::runtime_error naming the path if it cannot be opened or has no audio stream.
DecodedAudio decodeAudio(const std::filesystem::path& path);

}  // namespace coinroll::video
