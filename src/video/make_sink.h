#pragma once
// Picks the sink for an output path, as `coinroll render -o PATH` does.

#include <filesystem>
#include <memory>
#include <vector>

#include "video/frame_sink.h"
#include "video/mp4_sink.h"

namespace coinroll::video {

// A path whose file name has a % conversion ("out/frame_%05d.png") gives a PngSequenceSink; a path ending in
// ".mp4" (any case), or naming a device, FIFO or descriptor (/dev/null, /dev/stdout, /dev/fd/N),
// gives an Mp4Sink configured by `options` (the PNG sequence ignores them).
// Anything else throws std::invalid_argument naming the path and the two accepted forms; the
// sinks' constructors throw for a bad pattern, bad options or a missing directory.
// `inputs`: the command's input files, which no frame of a sequence may lead to.
std::unique_ptr<FrameSink> makeSinkForPath(const std::filesystem::path& path, const Mp4Options& options,
                                           const std::vector<std::filesystem::path>& inputs = {});

}  // namespace coinroll::video
