#pragma once
// The video kinds coinroll writes, one row each (docs/outputs.md "Video formats"): how a name
// chooses it, what it is called, its muxer, encoder, pixel formats and options, what it can carry
// and the memory its encoder holds. Everything that differs between kinds is read from here: the
// sink's set-up, the output-name rule, --help and every message that lists or refuses kinds.
// Plain data, no libav types, so the command line can read it.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "video/video_options.h"

namespace coinroll::video {

// Name and value pairs in libav's own spelling, set in order.
using LibavOptions = std::vector<std::pair<std::string, std::string>>;

struct VideoKind {
  VideoFormat format;
  std::string_view extension;         // ".mp4": a name ending so, in any case, is written as this kind
  std::string_view label;             // "MP4": the kind in messages
  std::string_view article;           // "an": as --help says "an MP4"
  std::string_view codec;             // "H.264" in --help; empty where the kind is named after its codec (GIF)
  std::string_view muxer;             // libavformat's name; the temporary name has no extension to guess by
  std::string_view encoder;           // libavcodec's name
  std::string_view pixelFormat;       // libav's name, for opaque frames
  std::string_view alphaPixelFormat;  // for frames that keep their alpha; empty where the kind has none
  bool audio;                         // holds a sound track (AAC)
  bool indexFirst;                    // the index before the media (+faststart): players start before the download ends
  bool loops;                         // plays for ever
  // The highest frame rate the kind shows as written, 0 for any, and why, for the refusal.
  int maxFps;
  std::string_view maxFpsReason;
  // The muxer's option for how long the last frame lasts, where the muxer does not take it from the
  // packet's duration (GIF's repeats the delay before it); empty where it does.
  std::string_view lastFrameOption;
  // The encoder's options for `options`, set with libav's option search: the encoder's own
  // options first (x264's "preset"), then the codec context's ("threads").
  LibavOptions (*encoderOptions)(const VideoOptions& options);
  // The encoder's working memory (lookahead, references), in frames of RGBA bytes.
  std::uint64_t (*framesInFlight)(const VideoOptions& options);
  // Writes the provenance into the finished file, where the muxer drops the container's comment
  // tag (GIF); nullptr where the tag is kept.
  void (*addComment)(const std::filesystem::path& file, std::string_view comment);

  bool keepsAlpha() const { return !alphaPixelFormat.empty(); }
  bool carriesFps(int fps) const { return maxFps == 0 || fps <= maxFps; }
};

// Every kind, in the order of VideoFormat: the order names are matched and kinds listed in.
std::span<const VideoKind> videoKinds();
const VideoKind& videoKind(VideoFormat format);

// The one rule for an output's extension: the name's extension (the part of its file name from the
// last dot, a leading dot excepted) equals `extension` in any case, as .GIF is a GIF.
bool namesExtension(const std::filesystem::path& name, std::string_view extension);

// Stills, PNG sequences and compare's diff image.
inline constexpr std::string_view kPngExtension = ".png";

// "a, b or c": a list in a message.
std::string joinedWithOr(std::span<const std::string> items);

// Throws std::invalid_argument in the words of the scene's render block when `format` cannot carry
// what `wanted` asks for (docs/outputs.md): alpha (render.background "transparent"), a sound track
// (render.audio) or its frame rate (render.fps); each message names the kinds that can, and
// `soundOff` how the caller's user leaves the sound out.
void refuseOutputThatCannotCarry(const VideoOptions& wanted, VideoFormat format,
                                 std::string_view soundOff = "--set render.audio=null");

}  // namespace coinroll::video
