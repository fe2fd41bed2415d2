#pragma once
// A scene file's bytes to its JSON document, before any key is looked at: the size cap, NUL bytes,
// syntax errors with their line and column, and keys given twice (nlohmann would keep the last).

#include <nlohmann/json.hpp>

#include <filesystem>
#include <istream>
#include <string_view>

namespace coinroll::scene {

// The JSON document of a scene file, before validation. A syntax error is reported with its line
// and column.
nlohmann::json readSceneDocument(const std::filesystem::path& file);

// The same from a stream already open (standard input), its messages naming `sourceName`.
nlohmann::json readSceneDocument(std::istream& in, std::string_view sourceName);

// The JSON document in `text`; a syntax error names `sourceName`, the line and the column.
nlohmann::json parseSceneText(std::string_view text, std::string_view sourceName);

}  // namespace coinroll::scene
