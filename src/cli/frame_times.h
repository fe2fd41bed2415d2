#pragma once
// render --frame-times FILE.csv: the frame times the program chose, one row per frame of the video
// it wrote, so a tool that lines the video up with the simulation reads them instead of repeating
// the time-remap rule (docs/outputs.md "Frame times"). The sidecar is one of the run's outputs: it
// is staged in the group the video's files are, and published with them or not at all.

#include <string>

#include "io/output_file.h"
#include "io/output_group.h"
#include "pipeline/video_frames.h"

namespace coinroll::cli {

// The header, units in the names: frame,video_time_s,clip_frame,sim_time_s,playback_rate.
inline constexpr const char* kFrameTimesHeader = "frame,video_time_s,clip_frame,sim_time_s,playback_rate";

class FrameTimesSidecar {
 public:
  // Opens the temporary, staged in `outputs` (a name that cannot be written fails here, before any
  // work), and writes the header.
  FrameTimesSidecar(const std::string& path, int fps, io::OutputGroup& outputs);

  void add(const pipeline::FrameTiming& timing);  // one row; a failed write throws, naming the file

  // Completes the file for `outputs`' commit(), which publishes it with the video.
  void finish();

 private:
  io::OutputFile file_;
  int fps_;
};

}  // namespace coinroll::cli
