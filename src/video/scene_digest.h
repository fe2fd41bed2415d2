#pragma once
// Which scene made an output: the scene digest coinroll writes into its pictures and videos
// (Provenance: a PNG's tEXt chunk, a container's comment tag), read back, so that a default output
// name (a still's PNG, a render's MP4) is never silently taken over by another scene's output.

#include <filesystem>
#include <optional>
#include <string>

namespace coinroll::video {

// The scene digest ("fnv1a64:0123456789abcdef") the file at `path` carries: a PNG's
// coinroll-scene-digest text, or the comment tag of a container libavformat reads (MP4, MOV, WebM).
// None for a file coinroll did not make (or made with render.provenance: false), or that cannot be
// read; never throws for the file's content.
std::optional<std::string> readSceneDigest(const std::filesystem::path& path);

}  // namespace coinroll::video
