// Each video kind EncoderSink writes, decoded back: its codec, frame count, size, pixel format and
// alpha, pictures close to what was pushed, the same bytes from the same frames, and the
// provenance tags (docs/outputs.md "Video formats").

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "synthetic_frames.h"
#include "video/encoder_sink.h"
#include "video/gif_comment.h"
#include "video_probe.h"

namespace fs = std::filesystem;
using coinroll::image::Image;
using coinroll::video::EncoderSink;
using coinroll::video::VideoFormat;
using coinroll::video::VideoOptions;
using namespace coinroll::video::testing;

namespace {

constexpr int kWidth = 320, kHeight = 180, kFps = 30, kFrames = 20;

struct Kind {
  VideoFormat format;
  const char* file;
  const char* codec;        // FFmpeg's name for the stream's codec
  const char* pixelFormat;  // as the decoder reports the stream
  double maxRmsError;       // 8-bit levels, frame 10 against the frame pushed
};

// ProRes 4444 decodes at 12 bits whatever it was coded from; the GIF decoder gives BGRA, and the
// dither of a 252-colour palette costs most.
const Kind kKinds[] = {
    {VideoFormat::Mp4, "clip.mp4", "h264", "yuv420p", 4.5},
    {VideoFormat::Gif, "clip.gif", "gif", "bgra", 30},
    {VideoFormat::WebM, "clip.webm", "vp9", "yuv420p", 8},
    {VideoFormat::Mov, "clip.mov", "prores", "yuv444p12le", 2},
};

VideoOptions optionsFor(VideoFormat format) {
  VideoOptions options;
  options.format = format;
  options.width = kWidth;
  options.height = kHeight;
  options.fps = kFps;
  return options;
}

// The moving square, its alpha a ramp from 0 at the left edge to 255 at the right.
Image translucentFrame(int index) {
  Image frame = movingSquareFrame(kWidth, kHeight, index);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) frame.pixel(x, y)[3] = static_cast<std::uint8_t>(255 * x / (kWidth - 1));
  }
  return frame;
}

void encode(const fs::path& path, const VideoOptions& options) {
  EncoderSink sink(path, options);
  for (int i = 0; i < kFrames; ++i)
    sink.push(options.alpha ? translucentFrame(i) : movingSquareFrame(kWidth, kHeight, i));
  sink.finish();
}

std::string bytesOf(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// Matroska's tags are upper case, MP4's and MOV's lower case.
std::string tagOf(const coinroll::video::VideoInfo& info, std::string key) {
  for (const auto& [name, value] : info.tags) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    if (lower == key) return value;
  }
  return {};
}

double rmsErrorAlpha(const Image& reference, const Image& test) {
  double squaredError = 0;
  for (std::size_t i = 3; i < reference.rgba.size(); i += 4) {
    const double difference = double(reference.rgba[i]) - double(test.rgba[i]);
    squaredError += difference * difference;
  }
  return std::sqrt(squaredError / double(reference.rgba.size() / 4));
}

TEST(VideoFormats, EachDecodesBackWithItsCodecFramesSizeAndPixelFormat) {
  ScratchDirectory directory;
  for (const Kind& kind : kKinds) {
    const fs::path path = directory.path() / kind.file;
    encode(path, optionsFor(kind.format));
    const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(path);
    EXPECT_EQ(info.codecName, kind.codec) << kind.file;
    EXPECT_EQ(info.pixelFormat, kind.pixelFormat) << kind.file;
    EXPECT_EQ(info.width, kWidth) << kind.file;
    EXPECT_EQ(info.height, kHeight) << kind.file;
    EXPECT_EQ(info.frameCount, kFrames) << kind.file;
    // The GIF decoder gives BGRA whatever the file holds; the picture decodes opaque all the same.
    EXPECT_EQ(info.alpha, kind.format == VideoFormat::Gif) << kind.file;
    EXPECT_EQ(info.moovBeforeMdat, kind.format == VideoFormat::Mp4 || kind.format == VideoFormat::Mov) << kind.file;
    const Image decoded = coinroll::video::decodeFrame(path, 10);
    EXPECT_LT(rmsErrorRgb(movingSquareFrame(kWidth, kHeight, 10), decoded), kind.maxRmsError) << kind.file;
    long translucent = 0;
    for (std::size_t i = 3; i < decoded.rgba.size(); i += 4) translucent += decoded.rgba[i] != 255 ? 1 : 0;
    EXPECT_EQ(translucent, 0) << kind.file;
    // The last frame is there too.
    EXPECT_NO_THROW(coinroll::video::decodeFrame(path, kFrames - 1)) << kind.file;
  }
}

TEST(VideoFormats, EachIsByteIdenticalForTheSameFrames) {
  ScratchDirectory directory;
  for (const Kind& kind : kKinds) {
    const fs::path a = directory.path() / ("a_" + std::string(kind.file)),
                   b = directory.path() / ("b_" + std::string(kind.file));
    encode(a, optionsFor(kind.format));
    encode(b, optionsFor(kind.format));
    EXPECT_EQ(bytesOf(a), bytesOf(b)) << kind.file << " differs between two encodings of the same frames";
  }
}

TEST(VideoFormats, WebmAndMovKeepTheFramesAlpha) {
  ScratchDirectory directory;
  for (const auto& [format, file, pixelFormat, maxAlphaError] :
       {std::tuple{VideoFormat::WebM, "alpha.webm", "yuv420p", 3.0},
        std::tuple{VideoFormat::Mov, "alpha.mov", "yuva444p12le", 1.0}}) {
    VideoOptions options = optionsFor(format);
    options.alpha = true;
    const fs::path path = directory.path() / file;
    encode(path, options);
    const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(path);
    EXPECT_TRUE(info.alpha) << file;
    EXPECT_EQ(info.pixelFormat, pixelFormat) << file;  // VP9's alpha travels beside its yuv420p picture
    EXPECT_EQ(info.frameCount, kFrames) << file;
    const Image decoded = coinroll::video::decodeFrame(path, 10);
    EXPECT_LT(rmsErrorAlpha(translucentFrame(10), decoded), maxAlphaError) << file;
    EXPECT_LE(decoded.pixel(0, kHeight / 2)[3], 8) << file << ": the left edge is transparent";
    EXPECT_GE(decoded.pixel(kWidth - 1, kHeight / 2)[3], 247) << file << ": the right edge is opaque";
    // Alpha costs no determinism.
    const fs::path again = directory.path() / ("again_" + std::string(file));
    encode(again, options);
    EXPECT_EQ(bytesOf(path), bytesOf(again)) << file;
  }
}

TEST(VideoFormats, AlphaAndAudioAreRefusedWhereTheContainerHasNone) {
  ScratchDirectory directory;
  for (const VideoFormat format : {VideoFormat::Mp4, VideoFormat::Gif}) {
    VideoOptions options = optionsFor(format);
    options.alpha = true;
    EXPECT_THROW(coinroll::video::validate(options), std::invalid_argument);
  }
  for (const VideoFormat format : {VideoFormat::Gif, VideoFormat::WebM}) {
    VideoOptions options = optionsFor(format);
    options.audio = true;
    EXPECT_THROW(coinroll::video::validate(options), std::invalid_argument);
  }
  EXPECT_TRUE(fs::is_empty(directory.path()));
}

TEST(VideoFormats, ProvenanceNamesTheReleaseAndTheSceneAndIsLeftOutWhenEmpty) {
  ScratchDirectory directory;
  for (const Kind& kind : kKinds) {
    if (kind.format == VideoFormat::Gif) continue;  // no tags: a comment extension (the test below)
    VideoOptions options = optionsFor(kind.format);
    options.provenance = {.software = "coinroll 9.9.9", .sceneDigest = "fnv1a64:0123456789abcdef"};
    const fs::path tagged = directory.path() / ("tagged_" + std::string(kind.file));
    encode(tagged, options);
    const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(tagged);
    EXPECT_EQ(tagOf(info, "comment"), "coinroll 9.9.9, scene fnv1a64:0123456789abcdef") << kind.file;
    // libavformat drops "encoder" from a bit-exact MP4; MOV and WebM keep ours (never Lavf's).
    EXPECT_EQ(tagOf(info, "encoder"), kind.format == VideoFormat::Mp4 ? "" : "coinroll 9.9.9") << kind.file;

    const fs::path plain = directory.path() / ("plain_" + std::string(kind.file));
    encode(plain, optionsFor(kind.format));
    const coinroll::video::VideoInfo untagged = coinroll::video::readVideoInfo(plain);
    EXPECT_EQ(tagOf(untagged, "comment"), "") << kind.file;
    // Matroska names its muxer whatever it is told: "Lavf", never with a version.
    EXPECT_EQ(tagOf(untagged, "encoder"), kind.format == VideoFormat::WebM ? "Lavf" : "") << kind.file;
  }
}

// FFmpeg's GIF muxer writes no comment: the sink adds a Comment Extension to the finished file,
// which decoders skip (the frames decode as before) and a reader of the bytes finds.
TEST(VideoFormats, GifCarriesTheProvenanceInACommentExtensionAndDecodesTheSame) {
  ScratchDirectory directory;
  VideoOptions options = optionsFor(VideoFormat::Gif);
  options.provenance = {.software = "coinroll 9.9.9", .sceneDigest = "fnv1a64:0123456789abcdef"};
  const fs::path tagged = directory.path() / "tagged.gif";
  encode(tagged, options);
  const fs::path plain = directory.path() / "plain.gif";
  encode(plain, optionsFor(VideoFormat::Gif));
  EXPECT_EQ(coinroll::video::gifComment(bytesOf(tagged)), "coinroll 9.9.9, scene fnv1a64:0123456789abcdef");
  EXPECT_EQ(coinroll::video::gifComment(bytesOf(plain)), "");
  // Introducer, label, one sub-block (its length and the text), terminator.
  EXPECT_EQ(bytesOf(tagged).size(), bytesOf(plain).size() + 2 + 1 + options.provenance.comment().size() + 1);
  EXPECT_EQ(coinroll::video::readVideoInfo(tagged).frameCount, kFrames);
  for (const int frame : {0, kFrames - 1}) {
    EXPECT_EQ(coinroll::video::decodeFrame(tagged, frame).rgba, coinroll::video::decodeFrame(plain, frame).rgba)
        << frame;
  }
}

TEST(GifComment, ALongCommentIsSplitIntoSubBlocksOfAtMost255BytesAndReadBackWhole) {
  // The smallest GIF89a header: a 1x1 screen with a 2-colour table, then the trailer.
  const std::string gif = std::string("GIF89a\x01\x00\x01\x00\x80\x00\x00", 13) + std::string(6, '\0') + ";";
  const std::string comment(600, 'c');
  const std::string tagged = coinroll::video::withGifComment(gif, comment);
  EXPECT_EQ(coinroll::video::gifComment(tagged), comment);
  EXPECT_EQ(tagged.substr(19, 2), "\x21\xfe");             // after the 6-byte colour table
  EXPECT_EQ(static_cast<unsigned char>(tagged[21]), 255);  // first sub-block full
  EXPECT_EQ(tagged.size(), gif.size() + 2 + (1 + 255) * 2 + (1 + 90) + 1);
  EXPECT_THROW(coinroll::video::withGifComment("GIF87a", comment), std::invalid_argument);
}

// A GIF times each frame in whole hundredths of a second, and browsers play a delay under 2 as 10
// (a 60 fps GIF alternated 2, 1, 2: 2.8x too slow). So every delay, decoded back from the bytes, is
// at least 2, and each frame ends at its own time, k / fps, to the nearest hundredth: the delays add
// up to the clip's length, the last included. A rate that needs shorter delays is refused, for every
// rate render.fps allows (1..240), with nothing written.
TEST(VideoFormats, GifFramesLastWholeHundredthsOfAtLeastTwoAndEndAtTheirOwnTimes) {
  ScratchDirectory directory;
  constexpr int kSide = 16;
  for (int fps = 1; fps <= 240; ++fps) {
    VideoOptions options = optionsFor(VideoFormat::Gif);
    options.width = options.height = kSide;
    options.fps = fps;
    const fs::path path = directory.path() / ("fps_" + std::to_string(fps) + ".gif");
    if (fps > 50) {
      EXPECT_THROW((EncoderSink{path, options}), std::invalid_argument) << fps << " fps";
      continue;
    }
    const int frames = fps + 3;  // a little over a second: every phase of the rounding
    {
      EncoderSink sink(path, options);
      for (int i = 0; i < frames; ++i) sink.push(movingSquareFrame(kSide, kSide, i));
      sink.finish();
    }
    const std::vector<int> delays = coinroll::video::gifFrameDelays(path);
    ASSERT_EQ(delays.size(), static_cast<std::size_t>(frames)) << fps << " fps";
    int end = 0;  // hundredths of a second
    for (int k = 0; k < frames; ++k) {
      EXPECT_GE(delays[k], 2) << fps << " fps, frame " << k;
      end += delays[k];
      // |end - 100 (k + 1) / fps| <= 1/2, in whole numbers
      EXPECT_LE(std::abs(2 * fps * end - 200 * (k + 1)), fps)
          << fps << " fps: frame " << k << " ends at " << end << " cs";
    }
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(directory.path()), fs::directory_iterator()), 50);
}

TEST(VideoFormats, GifLoopsForEver) {
  ScratchDirectory directory;
  const fs::path path = directory.path() / "loop.gif";
  encode(path, optionsFor(VideoFormat::Gif));
  // The application extension NETSCAPE2.0: sub-block 3 bytes, id 1, loop count 0 (little endian) = for ever.
  const std::string bytes = bytesOf(path);
  const std::size_t at = bytes.find("NETSCAPE2.0");
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(bytes.substr(at + 11, 4), std::string("\x03\x01\x00\x00", 4));
}

}  // namespace
