#pragma once
// The files a run reads, which none of its outputs may replace (video::refuseOverwritingInput).

#include <filesystem>
#include <optional>
#include <vector>

namespace coinroll::pipeline {

// The scene file (none for a scene that came from elsewhere), and each file of $COINROLL_ASSET_DIR
// and $COINROLL_SHADER_DIR when set: a texture or a shader the renderer reads.
std::vector<std::filesystem::path> inputFiles(const std::optional<std::filesystem::path>& sceneFile);

}  // namespace coinroll::pipeline
