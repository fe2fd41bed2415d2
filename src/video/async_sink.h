#pragma once
// Runs another sink on its own thread, so encoding overlaps rendering.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <variant>
#include <vector>

#include "video/frame_sink.h"

namespace coinroll::video {

// Frames (and audio blocks) wait in a bounded queue (memory stays constant however long the clip): push() blocks
// while it is full. An exception thrown by the inner sink on the worker thread is rethrown by the
// next push() or finish(). Destroyed without finish(), the worker stops
// after the frame in hand, queued frames are dropped and the inner sink is destroyed unfinished,
// so it removes its partial output.
class AsyncSink final : public FrameSink {
 public:
  static constexpr std::size_t kDefaultCapacity = 4;  // frames; 4 x 3.7 MB at 1280x720

  // `capacity` >= 1 frames (std::invalid_argument otherwise).
  explicit AsyncSink(std::unique_ptr<FrameSink> inner, std::size_t capacity = kDefaultCapacity);
  ~AsyncSink() override;

  void push(const image::Image& frame) override;  // copies the frame
  void push(image::Image&& frame);                // takes the frame's pixels without copying
  // Queued with the frames, so the inner sink sees pictures and sound in the order pushed.
  void pushAudio(std::span<const float> samples) override;
  // Waits for the queue to drain, then finishes the inner sink (on the caller's thread).
  void finish() override;
  // The queue, the frame in the worker's hands and the copy push() makes, and the inner sink's.
  std::uint64_t workingMemory(std::uint64_t frameBytes) const override {
    return (capacity_ + 2) * frameBytes + inner_->workingMemory(frameBytes);
  }

 private:
  void runWorker();
  void rethrowWorkerError() const;  // requires mutex_ held

  std::unique_ptr<FrameSink> inner_;
  const std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable queueChanged_;
  using Item = std::variant<image::Image, std::vector<float>>;  // a frame or a block of audio
  void enqueue(Item item);
  std::deque<Item> queue_;
  std::exception_ptr workerError_;
  bool closing_ = false;    // no more frames will come; the worker drains the queue and exits
  bool abandoned_ = false;  // destroyed unfinished; the worker exits at once
  std::thread worker_;      // started by the constructor, joined by finish() or the destructor
};

}  // namespace coinroll::video
