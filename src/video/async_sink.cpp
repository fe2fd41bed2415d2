#include "video/async_sink.h"

#include <stdexcept>

namespace coinroll::video {

AsyncSink::AsyncSink(std::unique_ptr<FrameSink> inner, std::size_t capacity)
    : inner_(std::move(inner)), capacity_(capacity) {
  if (!inner_) throw std::invalid_argument("AsyncSink: no inner sink");
  if (capacity_ < 1) throw std::invalid_argument("AsyncSink: capacity must be >= 1 frame, got 0");
  worker_ = std::thread([this] { runWorker(); });
}

AsyncSink::~AsyncSink() {
  {
    std::lock_guard lock(mutex_);
    abandoned_ = true;
  }
  queueChanged_.notify_all();
  if (worker_.joinable()) worker_.join();
  // inner_ is destroyed after this body; an unfinished inner sink removes its output.
}

void AsyncSink::runWorker() {
  for (;;) {
    Item item;
    {
      std::unique_lock lock(mutex_);
      queueChanged_.wait(lock, [this] { return abandoned_ || closing_ || !queue_.empty(); });
      if (abandoned_ || queue_.empty()) return;  // queue empty here means closing_ and drained
      item = std::move(queue_.front());
      queue_.pop_front();
    }
    queueChanged_.notify_all();  // a slot is free
    try {
      if (const auto* frame = std::get_if<image::Image>(&item))
        inner_->push(*frame);
      else
        inner_->pushAudio(std::get<std::vector<float>>(item));
    } catch (...) {
      {
        std::lock_guard lock(mutex_);
        workerError_ = std::current_exception();
        queue_.clear();
      }
      queueChanged_.notify_all();
      return;
    }
  }
}

void AsyncSink::rethrowWorkerError() const {
  if (workerError_) std::rethrow_exception(workerError_);
}

void AsyncSink::push(const image::Image& frame) { push(image::Image(frame)); }

void AsyncSink::push(image::Image&& frame) { enqueue(std::move(frame)); }

void AsyncSink::pushAudio(std::span<const float> samples) {
  enqueue(std::vector<float>(samples.begin(), samples.end()));
}

void AsyncSink::enqueue(Item item) {
  {
    std::unique_lock lock(mutex_);
    if (closing_) throw std::logic_error("AsyncSink: push() after finish()");
    queueChanged_.wait(lock, [this] { return workerError_ || queue_.size() < capacity_; });
    rethrowWorkerError();
    queue_.push_back(std::move(item));
  }
  queueChanged_.notify_all();
}

void AsyncSink::finish() {
  {
    std::lock_guard lock(mutex_);
    if (closing_) throw std::logic_error("AsyncSink: finish() called twice");
    closing_ = true;
  }
  queueChanged_.notify_all();
  worker_.join();
  // The worker has exited, so its error (if any) is visible without racing it.
  {
    std::lock_guard lock(mutex_);
    rethrowWorkerError();
  }
  inner_->finish();
}

}  // namespace coinroll::video
