#include "cli/frame_times.h"

#include <fmt/format.h>

namespace coinroll::cli {

FrameTimesSidecar::FrameTimesSidecar(const std::string& path, int fps, io::OutputGroup& outputs)
    : file_(path, "frame times CSV", io::OutputFile::Access::Sequential, &outputs), fps_(fps) {
  file_.stream() << kFrameTimesHeader << '\n';
}

void FrameTimesSidecar::add(const pipeline::FrameTiming& timing) {
  // 17 significant digits give the doubles back exactly, so rows compare across renders bit for bit.
  file_.stream() << fmt::format("{},{:.17g},{},{:.17g},{:.17g}\n", timing.frame,
                                static_cast<double>(timing.frame) / fps_, timing.clipFrame, timing.simulatedTime,
                                timing.playbackRate);
}

void FrameTimesSidecar::finish() { file_.commit(); }

}  // namespace coinroll::cli
