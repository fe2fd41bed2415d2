#pragma once
// Provenance for GIFs: FFmpeg's GIF muxer writes no comment, so the sink adds a GIF89a Comment
// Extension to the finished file, as the other containers carry a comment tag.

#include <filesystem>
#include <string>
#include <string_view>

namespace coinroll::video {

// `gif` with a Comment Extension holding `comment` (plain text, split into sub-blocks of at most
// 255 bytes) placed after the Logical Screen Descriptor and its Global Color Table, before the
// NETSCAPE2.0 loop block and the frames, where every decoder skips it.
// std::invalid_argument if `gif` is not a GIF89a stream.
std::string withGifComment(std::string_view gif, std::string_view comment);

// The text of the first Comment Extension in `gif`; empty if it has none.
std::string gifComment(std::string_view gif);

// Rewrites the GIF file at `path` with the comment added; std::runtime_error naming the path and
// the system's reason when reading or writing it fails (a full disk).
void addGifComment(const std::filesystem::path& path, std::string_view comment);

}  // namespace coinroll::video
