#pragma once
// Picks the sink for an output path, as `coinroll render -o PATH` does, and keeps the rule every
// door (command, library, Python) holds its outputs to.

#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "video/encoder_sink.h"
#include "video/frame_sink.h"

namespace coinroll::video {

// The video kind a path names by its extension (namesExtension: any case; a % in such a name is a
// literal character: 100%.mp4), or the default kind (MP4) for a device, FIFO or descriptor
// (/dev/null, /dev/stdout, /dev/fd/N); nothing for a PNG sequence pattern or any other name.
std::optional<VideoFormat> videoFormatOf(const std::filesystem::path& path);

// A file name with a % conversion ("out/frame_%05d.png") that does not end in a video extension.
bool namesPngSequence(const std::filesystem::path& path);

// A video path gives an EncoderSink configured by `options` with the path's kind as its format;
// a PNG sequence pattern gives a PngSequenceSink (which takes only the provenance and the frames'
// alpha as they are). Anything else throws std::invalid_argument naming the path and the accepted
// forms; the sinks' constructors throw for a bad pattern, bad options or a missing directory.
// `inputs`: the command's input files, which no frame of a sequence may lead to. With a `group`,
// the sink's files are staged in it and published by its commit(), not by the sink's finish().
// An output must never replace a file the caller reads: throws std::invalid_argument, before
// anything runs, when `output` is one of `inputs` (through any link) or names a PNG sequence one of
// whose frames would be. `argument` names the output as the caller's user gives it ("-o",
// "--csv", "output").
void refuseOverwritingInput(std::string_view argument, const std::filesystem::path& output,
                            const std::vector<std::filesystem::path>& inputs);

std::unique_ptr<FrameSink> makeSinkForPath(const std::filesystem::path& path, const VideoOptions& options,
                                           const std::vector<std::filesystem::path>& inputs = {},
                                           io::OutputGroup* group = nullptr);

}  // namespace coinroll::video
