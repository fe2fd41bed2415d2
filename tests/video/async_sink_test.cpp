#include "video/async_sink.h"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "synthetic_frames.h"
#include "video/mp4_sink.h"
#include "video/png_sequence_sink.h"

using coinroll::image::Image;
using coinroll::video::AsyncSink;
using coinroll::video::FrameSink;
using namespace coinroll::video::testing;

namespace {

// Records what reaches it; fails on a chosen frame.
class RecordingSink final : public FrameSink {
 public:
  RecordingSink(std::atomic<int>& pushed, bool& finished, int failAtFrame = -1)
      : pushed_(pushed), finished_(finished), failAtFrame_(failAtFrame) {}
  void push(const Image& frame) override {
    if (pushed_ == failAtFrame_) throw std::runtime_error("disk full at frame " + std::to_string(pushed_.load()));
    if (frame.rgba[0] != static_cast<std::uint8_t>(pushed_.load())) throw std::logic_error("frames out of order");
    ++pushed_;
  }
  void finish() override { finished_ = true; }

 private:
  std::atomic<int>& pushed_;
  bool& finished_;
  int failAtFrame_;
};

Image numberedFrame(int index) {
  Image frame(4, 2);
  frame.rgba[0] = static_cast<std::uint8_t>(index);
  return frame;
}

}  // namespace

TEST(AsyncSink, DeliversEveryFrameInOrderThenFinishes) {
  std::atomic<int> pushed = 0;
  bool finished = false;
  AsyncSink sink(std::make_unique<RecordingSink>(pushed, finished), 2);
  for (int i = 0; i < 50; ++i) sink.push(numberedFrame(i));
  sink.finish();
  EXPECT_EQ(pushed, 50);
  EXPECT_TRUE(finished);
}

TEST(AsyncSink, MovedFramesArriveIntact) {
  std::atomic<int> pushed = 0;
  bool finished = false;
  AsyncSink sink(std::make_unique<RecordingSink>(pushed, finished));
  for (int i = 0; i < 10; ++i) {
    Image frame = numberedFrame(i);
    sink.push(std::move(frame));
  }
  sink.finish();
  EXPECT_EQ(pushed, 10);
}

TEST(AsyncSink, WorkerExceptionIsRethrownByALaterCall) {
  std::atomic<int> pushed = 0;
  bool finished = false;
  AsyncSink sink(std::make_unique<RecordingSink>(pushed, finished, 3));
  try {
    for (int i = 0; i < 100; ++i) sink.push(numberedFrame(i));
    sink.finish();
    FAIL() << "the worker's exception was lost";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "disk full at frame 3");
  }
  EXPECT_FALSE(finished);
}

TEST(AsyncSink, DestroyedWithoutFinishLeavesNoOutput) {
  ScratchDirectory directory;
  {
    AsyncSink sink(std::make_unique<coinroll::video::PngSequenceSink>(directory / "f_%03d.png"));
    for (int i = 0; i < 6; ++i) sink.push(movingSquareFrame(32, 18, i));
  }
  EXPECT_EQ(directory.fileCount(), 0);
}

TEST(AsyncSink, Mp4ThroughTheWorkerIsByteIdenticalToDirect) {
  ScratchDirectory directory;
  coinroll::video::Mp4Options options;
  options.width = 160;
  options.height = 90;
  {
    coinroll::video::Mp4Sink direct(directory / "direct.mp4", options);
    AsyncSink async(std::make_unique<coinroll::video::Mp4Sink>(directory / "async.mp4", options));
    for (int i = 0; i < 15; ++i) {
      direct.push(movingSquareFrame(160, 90, i));
      async.push(movingSquareFrame(160, 90, i));
    }
    direct.finish();
    async.finish();
  }
  auto bytes = [](const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  };
  const std::vector<char> direct = bytes(directory / "direct.mp4");
  ASSERT_FALSE(direct.empty());
  EXPECT_TRUE(direct == bytes(directory / "async.mp4"));
}
