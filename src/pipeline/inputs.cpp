#include "pipeline/inputs.h"

#include <cstdlib>

namespace coinroll::pipeline {

std::vector<std::filesystem::path> inputFiles(const std::optional<std::filesystem::path>& sceneFile) {
  std::vector<std::filesystem::path> inputs;
  if (sceneFile) inputs.push_back(*sceneFile);
  for (const char* variable : {"COINROLL_ASSET_DIR", "COINROLL_SHADER_DIR"}) {
    const char* directory = std::getenv(variable);
    if (directory == nullptr || *directory == '\0') continue;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
      if (entry.is_regular_file(error)) inputs.push_back(entry.path());
    }
  }
  return inputs;
}

}  // namespace coinroll::pipeline
