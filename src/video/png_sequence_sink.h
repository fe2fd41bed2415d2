#pragma once
// A numbered sequence of PNG files, one per frame.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/output_group.h"

#include "video/frame_sink.h"
#include "video/video_options.h"

namespace coinroll::video {

// The file names of a PNG sequence: a file name with exactly one printf-style integer conversion,
// %d or %0Nd (N = minimum digits, zero-padded, 1..10), ending in ".png" in any case; "%%" is a
// literal percent sign. Frame i is named prefix, i with at least minimumDigits digits, suffix.
struct SequencePattern {
  std::string prefix;     // file name before the number, escapes resolved
  std::string suffix;     // file name after the number
  int minimumDigits = 0;  // N of %0Nd; 0 for %d

  std::string fileNameOf(int index) const;
  // The frame a file name is, when it is exactly the name fileNameOf gives that number
  // ("f_0004.png" is no frame of f_%03d.png); nothing for any other name.
  std::optional<int> frameNumberOf(std::string_view fileName) const;
};

// The pattern of `pattern`'s file name (its directory part is not looked at). Throws
// std::invalid_argument naming `pattern` and the rule it breaks.
SequencePattern parseSequencePattern(const std::filesystem::path& pattern);

// `pattern` is a path whose file name holds exactly one printf-style integer conversion, %d or
// %0Nd (N = minimum digits, zero-padded), and ends in ".png"; "%%" is a literal percent sign
// there. The directory part is taken literally, '%' included.
// Frames are numbered from 0: "out/frame_%05d.png" gives out/frame_00000.png, frame_00001.png, ...
//
// The sequence is all or nothing (io::OutputGroup, docs/outputs.md). Each frame is written as it
// arrives under a hidden temporary name beside its final one, every write checked; finish()
// renames them all into place (thousands a second: renames are cheap) and removes the frames of
// an earlier, longer sequence with this pattern that the new one does not reach (the names
// pathOfFrame gives for numbers from the frame count on, and no other file), so the directory
// holds exactly this sequence. If any of that fails, the renames already done are undone.
// Destroyed without finish(), the sink removes only its temporaries, so an interrupted or failed
// render leaves the directory as it was. With a `group`, the frames are staged in it, and the
// group's commit() publishes them along with the run's other outputs (a sidecar), all or none;
// finish() then only stages the removal of the earlier sequence's higher-numbered frames.
class PngSequenceSink final : public FrameSink {
 public:
  // Throws std::invalid_argument naming the pattern if it is malformed, std::runtime_error if its
  // directory does not exist. A frame's name may be a link (its target is written, as for any
  // output) but not a device, FIFO or descriptor: frames are published by renames. No frame may
  // lead to one of `inputs` or to another frame's file (io::OutputGroup::protect). Every frame
  // carries `provenance` as tEXt chunks (Provenance::pngText), and the alpha it is pushed with.
  explicit PngSequenceSink(std::filesystem::path pattern, const std::vector<std::filesystem::path>& inputs = {},
                           const Provenance& provenance = {}, io::OutputGroup* group = nullptr);
  ~PngSequenceSink() override;

  void push(const image::Image& frame) override;
  // Publishes the frames and removes the earlier sequence's higher-numbered ones, or changes
  // nothing and throws std::runtime_error; also when no frame was pushed.
  void finish() override;
  // Encoding one frame at a time: stb's filtered rows, its compressed output and our copy of it.
  std::uint64_t workingMemory(std::uint64_t frameBytes) const override { return 3 * frameBytes; }

  // The file frame `index` goes to.
  std::filesystem::path pathOfFrame(int index) const;

 private:
  std::filesystem::path directory_;
  SequencePattern pattern_;
  image::PngText text_;
  io::OutputGroup ownFrames_{"PNG"};  // the frames' group when the sink is given none
  io::OutputGroup& frames_;
  int frameCount_ = 0;
  bool finished_ = false;

  // Frames with this pattern already in the directory numbered `count` or more: those of an
  // earlier, longer sequence that this one replaces.
  std::vector<std::filesystem::path> framesFrom(int count) const;
};

// True if `fileName` contains a '%' other than a "%%" escape, i.e. it is meant as a sequence pattern.
bool looksLikeSequencePattern(const std::string& fileName);

}  // namespace coinroll::video
