#pragma once
// JSON scene documents to SceneConfig: each block validated against the scene schema
// (scene_schema.h), defaults filled in. Every error is a SceneError whose message names the source,
// the key path, the rule and the offending value ("scene.json: coin.radius: must be > 0, got -1").

#include <nlohmann/json.hpp>

#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/scene_config.h"
#include "scene/scene_error.h"
#include "scene/scene_override.h"
#include "scene/scene_text.h"

namespace coinroll::scene {

// Validates `document` and fills defaults; `sourceName` prefixes every message.
SceneConfig parseScene(const nlohmann::json& document, std::string_view sourceName);

// Reads `file`, applies `overrides` ("key.path=value") in order, then parses. A JSON syntax
// error is reported with its line and column.
SceneConfig loadScene(const std::filesystem::path& file, std::span<const std::string> overrides);

// The scene `coinroll render` uses without a file: a coin that rolls, wobbles and leaves a trace.
nlohmann::json builtInDefaultScene();

}  // namespace coinroll::scene
