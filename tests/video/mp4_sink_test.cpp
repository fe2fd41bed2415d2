#include "video/encoder_sink.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "synthetic_frames.h"
#include "tolerance.h"
#include "video_probe.h"

namespace fs = std::filesystem;
using coinroll::image::Image;
using coinroll::video::EncoderSink;
using coinroll::video::VideoOptions;
using namespace coinroll::video::testing;
using coinroll::testing::isBelow;
using coinroll::testing::isNear;

namespace {

constexpr int kWidth = 320, kHeight = 180, kFps = 30, kFrames = 60;

VideoOptions smallOptions() {
  VideoOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.fps = kFps;
  options.x264.crf = 18;
  options.x264.preset = "veryfast";
  return options;
}

void encodeMovingSquare(const fs::path& path, int frames, const VideoOptions& options = smallOptions()) {
  EncoderSink sink(path, options);
  for (int i = 0; i < frames; ++i) sink.push(movingSquareFrame(options.width, options.height, i));
  sink.finish();
}

std::vector<char> fileBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

std::string messageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "(no exception)";
}

}  // namespace

TEST(EncoderSink, WritesConstantRateH264WithBt709TagsAndMoovFirst) {
  ScratchDirectory directory;
  const fs::path path = directory / "clip.mp4";
  encodeMovingSquare(path, kFrames);

  const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(path);
  EXPECT_EQ(info.codecName, "h264");
  EXPECT_EQ(info.pixelFormat, "yuv420p");
  EXPECT_EQ(info.width, kWidth);
  EXPECT_EQ(info.height, kHeight);
  EXPECT_EQ(info.frameCount, kFrames);
  EXPECT_NEAR(info.durationSeconds, 2.0, 1.0 / kFps);
  EXPECT_DOUBLE_EQ(info.fps, kFps);
  EXPECT_EQ(info.colorPrimaries, "bt709");
  EXPECT_EQ(info.colorTransfer, "bt709");
  EXPECT_EQ(info.colorSpace, "bt709");
  EXPECT_EQ(info.colorRange, "tv");
  EXPECT_TRUE(info.moovBeforeMdat);
  EXPECT_EQ(directory.fileCount(), 1) << "a temporary file was left beside the video";
}

// One line per entry, "key=value", as FFmpeg's own command-line reader ffprobe (tools/setup.sh
// installs it with ffmpeg) reads the file: a second demuxer, independent of video_probe.
std::string ffprobe(const fs::path& path, const std::string& stream, const std::string& entries) {
  const std::string command = "ffprobe -v error -select_streams " + stream + " -show_entries " + entries +
                              " -of default=noprint_wrappers=1 '" + path.string() + "' 2>&1";
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
    pclose(pipe);
  }
  return output;
}

TEST(EncoderSink, FramesStartAtZeroAndTheLastLastsOneFramePeriod) {
  // N frames at fps: shown from t = 0, the last until N / fps exactly, as a player reads the file.
  ScratchDirectory directory;
  const fs::path path = directory / "clip.mp4";
  encodeMovingSquare(path, kFrames);
  EXPECT_EQ(ffprobe(path, "v:0", "stream=start_time,duration"), "start_time=0.000000\nduration=2.000000\n");
  EXPECT_TRUE(isNear(coinroll::video::readVideoInfo(path).durationSeconds, static_cast<double>(kFrames) / kFps, 1e-9));
}

TEST(EncoderSink, AudioTrackHoldsEverySamplePushedUpToTheLastShortBlock) {
  // AAC codes blocks of 1024 samples; 10 frames at 30 fps carry 16 000 samples, 15 whole blocks
  // and 640 over. A 1 kHz tone decoded back (the encoder's priming dropped) must keep all 16 000,
  // the last ones at the pushed amplitude too.
  constexpr int kSamples = 16000, kPerFrame = kSamples / 10;
  ScratchDirectory directory;
  const fs::path path = directory / "clip.mp4";
  VideoOptions options = smallOptions();
  options.audio = true;
  std::vector<float> tone(kSamples);
  for (int i = 0; i < kSamples; ++i)
    tone[i] = static_cast<float>(0.5 * std::sin(2 * std::numbers::pi * 1000.0 * i / 48000));
  {
    EncoderSink sink(path, options);
    for (int frame = 0; frame < 10; ++frame) {
      sink.push(movingSquareFrame(kWidth, kHeight, frame));
      sink.pushAudio(std::span<const float>(tone).subspan(static_cast<std::size_t>(frame) * kPerFrame, kPerFrame));
    }
    sink.finish();
  }
  const coinroll::video::DecodedAudio audio = coinroll::video::decodeAudio(path);
  EXPECT_EQ(audio.sampleRate, 48000);
  // The decoder returns whole blocks: every pushed sample, then at most one block's padding.
  ASSERT_GE(audio.samples.size(), static_cast<std::size_t>(kSamples));
  EXPECT_LT(audio.samples.size(), static_cast<std::size_t>(kSamples + 1024));
  // The last 400 samples (beyond the 15 whole blocks) still carry the tone: RMS 0.5 / sqrt 2.
  double squares = 0;
  for (int i = kSamples - 400; i < kSamples; ++i) squares += audio.samples[i] * audio.samples[i];
  EXPECT_TRUE(isNear(std::sqrt(squares / 400), 0.5 / std::sqrt(2.0), 0.05));
}

TEST(EncoderSink, SameFramesGiveByteIdenticalFiles) {
  ScratchDirectory directory;
  encodeMovingSquare(directory / "first.mp4", 20);
  encodeMovingSquare(directory / "second.mp4", 20);
  const std::vector<char> first = fileBytes(directory / "first.mp4");
  ASSERT_FALSE(first.empty());
  EXPECT_TRUE(first == fileBytes(directory / "second.mp4"));
}

TEST(EncoderSink, DecodedFramesMatchTheSourceAtCrf18) {
  // 4.5 levels RMS = PSNR 35 dB: crf 18 is "visually lossless", while a wrong matrix, range or
  // channel order costs tens of levels.
  constexpr double kMaxRmsErrorLevels = 4.5;
  ScratchDirectory directory;
  const fs::path path = directory / "clip.mp4";
  encodeMovingSquare(path, 30);
  for (const int index : {0, 17, 29}) {
    const Image decoded = coinroll::video::decodeFrame(path, index);
    EXPECT_TRUE(isBelow(rmsErrorRgb(movingSquareFrame(kWidth, kHeight, index), decoded), kMaxRmsErrorLevels))
        << "frame " << index;
  }
}

// Pure colours catch what a smooth gradient can hide: swapped channels, the BT.601 matrix
// where BT.709 is tagged, or full-range values tagged as limited range.
TEST(EncoderSink, PrimaryColoursDecodeToThemselves) {
  constexpr int kTolerance = 2;  // 8-bit levels: rounding to YUV and back; BT.601 for BT.709 is off by ~25
  struct Colour {
    std::uint8_t r, g, b;
  };
  const Colour colours[] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}, {0, 0, 0}, {128, 128, 128}};
  ScratchDirectory directory;
  const fs::path path = directory / "colours.mp4";
  VideoOptions options = smallOptions();
  options.x264.crf = 0;  // lossless, so only the colour conversion is being tested
  {
    EncoderSink sink(path, options);
    for (const Colour& c : colours) sink.push(solidFrame(kWidth, kHeight, c.r, c.g, c.b));
    sink.finish();
  }
  for (int i = 0; i < static_cast<int>(std::size(colours)); ++i) {
    const Image decoded = coinroll::video::decodeFrame(path, i);
    const std::uint8_t* p = decoded.pixel(kWidth / 2, kHeight / 2);
    EXPECT_TRUE(isNear(p[0], colours[i].r, kTolerance)) << "red of colour " << i;
    EXPECT_TRUE(isNear(p[1], colours[i].g, kTolerance)) << "green of colour " << i;
    EXPECT_TRUE(isNear(p[2], colours[i].b, kTolerance)) << "blue of colour " << i;
  }
}

TEST(EncoderSink, DestroyedWithoutFinishLeavesNoFile) {
  ScratchDirectory directory;
  {
    EncoderSink sink(directory / "clip.mp4", smallOptions());
    for (int i = 0; i < 5; ++i) sink.push(movingSquareFrame(kWidth, kHeight, i));
  }
  EXPECT_EQ(directory.fileCount(), 0);
}

TEST(EncoderSink, BadOptionsAreRefusedNamingTheField) {
  ScratchDirectory directory;
  const fs::path path = directory / "clip.mp4";
  auto messageFor = [&](auto change) {
    VideoOptions options = smallOptions();
    change(options);
    return messageOf([&] { EncoderSink sink(path, options); });
  };
  EXPECT_NE(messageFor([](VideoOptions& o) { o.width = 321; }).find("width"), std::string::npos);
  EXPECT_NE(messageFor([](VideoOptions& o) { o.height = 0; }).find("height"), std::string::npos);
  EXPECT_NE(messageFor([](VideoOptions& o) { o.fps = 0; }).find("fps"), std::string::npos);
  EXPECT_NE(messageFor([](VideoOptions& o) { o.x264.crf = 52; }).find("crf"), std::string::npos);
  EXPECT_NE(messageFor([](VideoOptions& o) { o.x264.threads = 0; }).find("threads"), std::string::npos);
  EXPECT_NE(messageFor([](VideoOptions& o) { o.x264.threads = 17; }).find("threads"), std::string::npos);  // 1..16
  EXPECT_NE(messageFor([](VideoOptions& o) { o.x264.preset = "speedy"; }).find("'speedy'"), std::string::npos);
  EXPECT_NE(messageFor([](VideoOptions& o) { o.x264.crf = -1; }).find("crf"), std::string::npos);
  EXPECT_EQ(directory.fileCount(), 0);
}

TEST(EncoderSink, MissingDirectoryIsReportedByPath) {
  ScratchDirectory directory;
  const fs::path path = directory / "no_such_directory" / "clip.mp4";
  EXPECT_NE(messageOf([&] { EncoderSink sink(path, smallOptions()); }).find(path.string()), std::string::npos);
}

TEST(EncoderSink, FrameOfTheWrongSizeIsRefused) {
  ScratchDirectory directory;
  EncoderSink sink(directory / "clip.mp4", smallOptions());
  EXPECT_THROW(sink.push(movingSquareFrame(kWidth * 2, kHeight, 0)), std::invalid_argument);
  EXPECT_THROW(sink.push(movingSquareFrame(kWidth, kHeight * 2, 0)), std::invalid_argument);
  EXPECT_THROW(sink.push(movingSquareFrame(kWidth, kHeight / 2, 0)), std::invalid_argument);
}

TEST(EncoderSink, FinishWithoutFramesThrowsAndLeavesNoFile) {
  ScratchDirectory directory;
  {
    EncoderSink sink(directory / "clip.mp4", smallOptions());
    EXPECT_THROW(sink.finish(), std::runtime_error);
  }
  EXPECT_EQ(directory.fileCount(), 0);
}

TEST(ReadVideoInfo, MissingFileIsReportedByPath) {
  ScratchDirectory directory;
  const fs::path path = directory / "absent.mp4";
  EXPECT_NE(messageOf([&] { coinroll::video::readVideoInfo(path); }).find(path.string()), std::string::npos);
}
