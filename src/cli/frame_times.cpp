#include "cli/frame_times.h"

#include <fmt/format.h>

#include <filesystem>
#include <system_error>
#include <utility>

namespace coinroll::cli {

class FrameTimesSidecar::PublishingSink final : public video::FrameSink {
 public:
  PublishingSink(std::unique_ptr<video::FrameSink> video, FrameTimesSidecar& sidecar)
      : video_(std::move(video)), sidecar_(sidecar) {}

  void push(const image::Image& frame) override { video_->push(frame); }
  void pushAudio(std::span<const float> samples) override { video_->pushAudio(samples); }
  std::uint64_t workingMemory(std::uint64_t frameBytes) const override { return video_->workingMemory(frameBytes); }

  void finish() override {
    sidecar_.publish();
    try {
      video_->finish();
    } catch (...) {
      sidecar_.withdraw();
      throw;
    }
  }

 private:
  std::unique_ptr<video::FrameSink> video_;
  FrameTimesSidecar& sidecar_;
};

FrameTimesSidecar::FrameTimesSidecar(const std::string& path, int fps) : file_(path, "frame times CSV"), fps_(fps) {
  file_.stream() << kFrameTimesHeader << '\n';
}

void FrameTimesSidecar::add(const pipeline::FrameTiming& timing) {
  // 17 significant digits give the doubles back exactly, so rows compare across renders bit for bit.
  file_.stream() << fmt::format("{},{:.17g},{},{:.17g},{:.17g}\n", timing.frame,
                                static_cast<double>(timing.frame) / fps_, timing.clipFrame, timing.simulatedTime,
                                timing.playbackRate);
}

std::unique_ptr<video::FrameSink> FrameTimesSidecar::publishedWith(std::unique_ptr<video::FrameSink> video) {
  return std::make_unique<PublishingSink>(std::move(video), *this);
}

void FrameTimesSidecar::publish() { file_.commit(); }

void FrameTimesSidecar::withdraw() noexcept {
  // A stream (a pipe, /dev/stdout) cannot take its bytes back; a file can go.
  if (file_.destination().isStream()) return;
  std::error_code ignored;
  std::filesystem::remove(file_.destination().path, ignored);
}

}  // namespace coinroll::cli
