#pragma once
// Picks the sink for an output path, as `coinroll render -o PATH` does.

#include <filesystem>
#include <memory>
#include <vector>

#include "video/frame_sink.h"
#include "video/mp4_sink.h"

namespace coinroll::video {

// A path ending in ".mp4" (any case; a % in it is a literal character: 100%.mp4), or naming a
// device, FIFO or descriptor (/dev/null, /dev/stdout, /dev/fd/N), gives an Mp4Sink configured by
// `options`; a path whose file name has a % conversion ("out/frame_%05d.png") gives a
// PngSequenceSink (which ignores them).
// Anything else throws std::invalid_argument naming the path and the two accepted forms; the
// sinks' constructors throw for a bad pattern, bad options or a missing directory.
// `inputs`: the command's input files, which no frame of a sequence may lead to.
bool namesPngSequence(const std::filesystem::path& path);
std::unique_ptr<FrameSink> makeSinkForPath(const std::filesystem::path& path, const Mp4Options& options,
                                           const std::vector<std::filesystem::path>& inputs = {});

}  // namespace coinroll::video
