#pragma once
// JSON scene files to SceneConfig. Every error is a SceneError whose message names the source,
// the key path, the rule and the offending value ("scene.json: coin.radius: must be > 0, got -1").

#include <nlohmann/json.hpp>

#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/scene_config.h"
#include "scene/scene_error.h"

namespace coinroll::scene {

// Validates `document` and fills defaults; `sourceName` prefixes every message.
SceneConfig parseScene(const nlohmann::json& document, std::string_view sourceName);

// The JSON document of a scene file, before validation. A syntax error is reported with its line
// and column.
nlohmann::json readSceneDocument(const std::filesystem::path& file);

// The JSON document in `text`; a syntax error names `sourceName`, the line and the column.
nlohmann::json parseSceneText(std::string_view text, std::string_view sourceName);

// Reads `file`, applies `overrides` ("key.path=value") in order, then parses. A JSON syntax
// error is reported with its line and column.
SceneConfig loadScene(const std::filesystem::path& file, std::span<const std::string> overrides);

// "initial.theta=12": the value is read as JSON when it parses as JSON, else taken as a string;
// missing objects along the path are created.
void applyOverride(nlohmann::json& document, std::string_view assignment);

// The scene `coinroll render` uses without a file: a coin that rolls, wobbles and leaves a trace.
nlohmann::json builtInDefaultScene();

}  // namespace coinroll::scene
