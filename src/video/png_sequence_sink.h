#pragma once
// A numbered sequence of PNG files, one per frame.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/atomic_file.h"

#include "video/frame_sink.h"

namespace coinroll::video {

// `pattern` is a path whose file name holds exactly one printf-style integer conversion, %d or
// %0Nd (N = minimum digits, zero-padded), and ends in ".png"; "%%" is a literal percent sign
// there. The directory part is taken literally, '%' included.
// Frames are numbered from 0: "out/frame_%05d.png" gives out/frame_00000.png, frame_00001.png, ...
//
// Each frame is written as it arrives under a hidden temporary name beside its final one, every
// write checked; finish() renames them all into place (thousands a second: renames are cheap).
// Destroyed without finish(), the sink removes only its temporaries, so an interrupted or failed
// render leaves no partial sequence and never touches files it did not write: files of an earlier
// run with the same names are replaced only when this run completes, and those it does not reach
// remain.
class PngSequenceSink final : public FrameSink {
 public:
  // Throws std::invalid_argument naming the pattern if it is malformed, std::runtime_error if its
  // directory does not exist.
  explicit PngSequenceSink(std::filesystem::path pattern);
  ~PngSequenceSink() override;

  void push(const image::Image& frame) override;
  void finish() override;

  // The file frame `index` goes to.
  std::filesystem::path pathOfFrame(int index) const;

 private:
  std::filesystem::path directory_;
  std::string prefix_;  // file name before the number
  std::string suffix_;  // file name after the number
  int minimumDigits_ = 0;
  std::vector<std::unique_ptr<io::AtomicOutputFile>> staged_;  // frame i's temporary, in order
  bool finished_ = false;
};

// True if `fileName` contains a '%' other than a "%%" escape, i.e. it is meant as a sequence pattern.
bool looksLikeSequencePattern(const std::string& fileName);

}  // namespace coinroll::video
