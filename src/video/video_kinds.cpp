#include "video/video_kinds.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <stdexcept>

#include "video/gif_comment.h"

extern "C" {
#include <libavutil/avutil.h>
}

namespace coinroll::video {

namespace {

LibavOptions x264Options(const VideoOptions& options) {
  return {{"threads", std::to_string(options.x264.threads)},
          {"preset", options.x264.preset},
          {"crf", std::to_string(options.x264.crf)}};
}

std::uint64_t x264FramesInFlight(const VideoOptions& options) {
  // Measured: the smallest address-space limit under which a 3 s, 960x540 clip is encoded, less
  // the renderer's and the queue's estimates, per RGBA byte of a frame: 6.4, 17.5, 31, 51, 62, 157
  // and 185 for ultrafast, veryfast, faster, medium, slow, veryslow and placebo (x264 0.164, one
  // thread); rounded up by a quarter, superfast, fast and slower taken between their neighbours.
  // More frames in flight (lookahead, references, B-frames) need more.
  constexpr std::array<std::uint64_t, kX264Presets.size()> kFramesOfMemory = {8, 12, 22, 39, 52, 64, 78, 132, 197, 232};
  const auto preset = std::find(kX264Presets.begin(), kX264Presets.end(), options.x264.preset);
  return kFramesOfMemory[static_cast<std::size_t>(preset - kX264Presets.begin())];
}

// libvpx-vp9's settings (measured in docs/outputs.md "Video formats"): the realtime deadline at its
// fastest speed with row multithreading keeps a WebM within 3x an MP4's time; crf with no bit-rate
// cap ("b" 0) is libvpx's constant-quality mode. Two threads, fixed as x264's are
// (X264Options::threads): the output must not follow the machine.
LibavOptions vp9Options(const VideoOptions&) {
  return {{"threads", "2"}, {"b", "0"}, {"deadline", "realtime"}, {"cpu-used", "8"}, {"row-mt", "1"}, {"crf", "32"}};
}

// ProRes's quantiser, 1 (finest) .. 31 (prores_ks's qscale); 4 is near-lossless for these pictures.
constexpr int kProResQuantiser = 4;

// One thread, as x264 (X264Options::threads): the renderer keeps the cores busy already. A fixed
// quantiser: prores_ks's default searches each slice's quantiser for the profile's bit budget, 6x
// slower for no visible gain (docs/outputs.md "Video formats").
LibavOptions proResOptions(const VideoOptions&) {
  return {{"threads", "1"},
          {"flags", "+qscale"},
          {"global_quality", std::to_string(kProResQuantiser * FF_QP2LAMBDA)},
          {"profile", "4444"}};
}

// gifflags' defaults (offsetting, transdiff) code only what changed since the last frame.
LibavOptions noOptions(const VideoOptions&) { return {}; }

// The other encoders were not measured as x264 was: VP9's realtime deadline looks ahead no frames
// and keeps a few references, ProRes codes each frame alone, GIF compares with the frame before;
// 16, 4 and 4 frames are generous estimates of that.
std::uint64_t sixteenFrames(const VideoOptions&) { return 16; }
std::uint64_t fourFrames(const VideoOptions&) { return 4; }

// A kind's fields are packed as a table reads, not laid out one a line.
// clang-format off
const auto kKinds = std::to_array<VideoKind>({
    {.format = VideoFormat::Mp4, .extension = ".mp4", .label = "MP4", .article = "an", .codec = "H.264",
     .muxer = "mp4", .encoder = "libx264", .pixelFormat = "yuv420p", .alphaPixelFormat = "",
     .audio = true, .indexFirst = true, .loops = false, .maxFps = 0, .maxFpsReason = "", .lastFrameOption = "",
     .encoderOptions = x264Options, .framesInFlight = x264FramesInFlight, .addComment = nullptr},
    {.format = VideoFormat::Gif, .extension = ".gif", .label = "GIF", .article = "a", .codec = "",
     .muxer = "gif", .encoder = "gif", .pixelFormat = "pal8", .alphaPixelFormat = "",
     .audio = false, .indexFirst = false, .loops = true, .maxFps = 50,
     .maxFpsReason = "its frame delays are whole hundredths of a second, and browsers play a delay under 2 as 10",
     .lastFrameOption = "final_delay",
     .encoderOptions = noOptions, .framesInFlight = fourFrames, .addComment = addGifComment},
    {.format = VideoFormat::WebM, .extension = ".webm", .label = "WebM", .article = "a", .codec = "VP9",
     .muxer = "webm", .encoder = "libvpx-vp9", .pixelFormat = "yuv420p", .alphaPixelFormat = "yuva420p",
     .audio = false, .indexFirst = false, .loops = false, .maxFps = 0, .maxFpsReason = "", .lastFrameOption = "",
     .encoderOptions = vp9Options, .framesInFlight = sixteenFrames, .addComment = nullptr},
    {.format = VideoFormat::Mov, .extension = ".mov", .label = "MOV", .article = "a", .codec = "ProRes 4444",
     .muxer = "mov", .encoder = "prores_ks", .pixelFormat = "yuv444p10le", .alphaPixelFormat = "yuva444p10le",
     .audio = true, .indexFirst = true, .loops = false, .maxFps = 0, .maxFpsReason = "", .lastFrameOption = "",
     .encoderOptions = proResOptions, .framesInFlight = fourFrames, .addComment = nullptr},
});
// clang-format on

// "a .webm, a .mov" for each kind `carries` accepts, then `also` when given.
std::string kindsThat(bool (*carries)(const VideoKind&, const VideoOptions&), const VideoOptions& wanted,
                      std::string_view also = {}) {
  std::vector<std::string> names;
  for (const VideoKind& kind : kKinds) {
    if (carries(kind, wanted)) names.push_back("a " + std::string(kind.extension));
  }
  if (!also.empty()) names.emplace_back(also);
  return joinedWithOr(names);
}

}  // namespace

std::span<const VideoKind> videoKinds() { return kKinds; }

const VideoKind& videoKind(VideoFormat format) {
  const auto row =
      std::find_if(kKinds.begin(), kKinds.end(), [&](const VideoKind& kind) { return kind.format == format; });
  if (row == kKinds.end()) throw std::logic_error("a VideoFormat without a row in video_kinds.cpp");
  return *row;
}

bool namesExtension(const std::filesystem::path& name, std::string_view extension) {
  const std::string own = name.extension().string();
  return std::equal(own.begin(), own.end(), extension.begin(), extension.end(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
  });
}

std::string joinedWithOr(std::span<const std::string> items) {
  std::string joined;
  for (std::size_t i = 0; i < items.size(); ++i) {
    joined += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  }
  return joined;
}

void refuseOutputThatCannotCarry(const VideoOptions& wanted, VideoFormat format, std::string_view soundOff) {
  const VideoKind& kind = videoKind(format);
  if (wanted.alpha && !kind.keepsAlpha()) {
    throw std::invalid_argument("render.background: \"transparent\" needs an output with alpha, and " +
                                std::string(kind.extension) + " has none; write " +
                                kindsThat([](const VideoKind& k, const VideoOptions&) { return k.keepsAlpha(); },
                                          wanted, "a PNG sequence (out_%05d.png)") +
                                ", or set render.background to \"opaque\"");
  }
  if (wanted.audio && !kind.audio) {
    throw std::invalid_argument("render.audio: a " + std::string(kind.extension) + " gets no sound track; write " +
                                kindsThat([](const VideoKind& k, const VideoOptions&) { return k.audio; }, wanted) +
                                ", or leave the sound out with " + std::string(soundOff));
  }
  if (!kind.carriesFps(wanted.fps)) {
    throw std::invalid_argument(
        "render.fps: a " + std::string(kind.extension) + " plays at most " + std::to_string(kind.maxFps) + " fps (" +
        std::string(kind.maxFpsReason) + "), got " + std::to_string(wanted.fps) + "; set render.fps to " +
        std::to_string(kind.maxFps) + " or less, or write " +
        kindsThat([](const VideoKind& k, const VideoOptions& w) { return k.carriesFps(w.fps); }, wanted));
  }
}

}  // namespace coinroll::video
