#pragma once
// render --frame-times FILE.csv: the frame times the program chose, one row per frame of the video
// it wrote, so a tool that lines the video up with the simulation reads them instead of repeating
// the time-remap rule (docs/outputs.md "Frame times"). Like simulate --provenance, the sidecar is
// written to a temporary and published only with the video: a failed run leaves neither.

#include <memory>
#include <string>

#include "io/output_file.h"
#include "pipeline/video_frames.h"
#include "video/frame_sink.h"

namespace coinroll::cli {

// The header, units in the names: frame,video_time_s,clip_frame,sim_time_s,playback_rate.
inline constexpr const char* kFrameTimesHeader = "frame,video_time_s,clip_frame,sim_time_s,playback_rate";

class FrameTimesSidecar {
 public:
  // Opens the temporary (a name that cannot be written fails here, before any work) and writes the header.
  FrameTimesSidecar(const std::string& path, int fps);

  void add(const pipeline::FrameTiming& timing);  // one row; a failed write throws, naming the file

  // Wraps the video's sink so this file takes its name just before the video does, and is removed
  // again when the video then fails to complete.
  std::unique_ptr<video::FrameSink> publishedWith(std::unique_ptr<video::FrameSink> video);

 private:
  class PublishingSink;
  void publish();
  void withdraw() noexcept;

  io::OutputFile file_;
  int fps_;
};

}  // namespace coinroll::cli
