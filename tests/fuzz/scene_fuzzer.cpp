// libFuzzer target: scene text and --set overrides through the same calls `coinroll` makes.
// Input layout: the JSON document, then zero or more NUL-separated "key.path=value" overrides.
// A SceneError is the documented outcome for bad input; anything else that escapes (another
// exception type, a crash, a sanitizer report) is a finding.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t documentEnd = std::min(input.find('\0'), input.size());
  std::vector<std::string_view> overrides;
  for (std::size_t start = documentEnd + 1; start <= input.size();) {
    const std::size_t end = std::min(input.find('\0', start), input.size());
    overrides.push_back(input.substr(start, end - start));
    start = end + 1;
  }

  try {
    nlohmann::json document = coinroll::scene::parseSceneText(input.substr(0, documentEnd), "fuzz.json");
    for (std::string_view assignment : overrides) coinroll::scene::applyOverride(document, assignment);
    coinroll::scene::parseScene(document, "fuzz.json");
  } catch (const coinroll::scene::SceneError&) {
  }
  return 0;
}
