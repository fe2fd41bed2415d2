#include "video/async_sink.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "synthetic_frames.h"
#include "video/encoder_sink.h"
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

TEST(AsyncSink, AnErrorOnTheLastFrameIsRethrownByFinish) {
  // Every push returns before the worker reaches the failing last frame; only finish() is left
  // to report it, and the inner sink must then stay unfinished.
  std::atomic<int> pushed = 0;
  bool finished = false;
  AsyncSink sink(std::make_unique<RecordingSink>(pushed, finished, 4), 8);
  for (int i = 0; i < 5; ++i) sink.push(numberedFrame(i));
  try {
    sink.finish();
    FAIL() << "the worker's exception was lost";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "disk full at frame 4");
  }
  EXPECT_FALSE(finished);
  EXPECT_EQ(pushed, 4);
}

// Holds the worker inside push() until released, counting the frames it has been handed.
class GatedSink final : public FrameSink {
 public:
  void push(const Image&) override {
    std::unique_lock lock(mutex_);
    ++entered_;
    changed_.notify_all();
    changed_.wait(lock, [this] { return open_; });
  }
  void finish() override {}
  void open() {
    {
      std::lock_guard lock(mutex_);
      open_ = true;
    }
    changed_.notify_all();
  }
  bool waitUntilEntered(int count) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, std::chrono::seconds(30), [&] { return entered_ >= count; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int entered_ = 0;
  bool open_ = false;
};

TEST(AsyncSink, AtMostCapacityFramesWaitBesideTheOneBeingWritten) {
  // The memory bound of async_sink.h: with the worker busy on one frame, `capacity` more fit in
  // the queue and the next push blocks until a slot frees.
  constexpr int kCapacity = 3;
  auto gated = std::make_unique<GatedSink>();
  GatedSink& inner = *gated;
  AsyncSink sink(std::move(gated), kCapacity);
  std::atomic<int> returned = 0;
  std::thread producer([&] {
    for (int i = 0; i < kCapacity + 3; ++i) {
      sink.push(numberedFrame(i));
      ++returned;
    }
  });
  ASSERT_TRUE(inner.waitUntilEntered(1));  // the worker holds frame 0
  for (int i = 0; i < 200 && returned < kCapacity + 1; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // time for a push that should block to return
  EXPECT_EQ(returned, kCapacity + 1);                           // frame 0 in hand, frames 1..capacity queued
  inner.open();
  producer.join();
  sink.finish();
  EXPECT_EQ(returned, kCapacity + 3);
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
  coinroll::video::VideoOptions options;
  options.width = 160;
  options.height = 90;
  {
    coinroll::video::EncoderSink direct(directory / "direct.mp4", options);
    AsyncSink async(std::make_unique<coinroll::video::EncoderSink>(directory / "async.mp4", options));
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
