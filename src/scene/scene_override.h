#pragma once
// `--set KEY.PATH=VALUE`: one change to a scene's JSON document before it is validated.

#include <nlohmann/json.hpp>

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace coinroll::scene {

// "initial.theta=12": the value is read as JSON when it parses as JSON, else taken as a string;
// missing objects along the path are created. The value null removes the key, so the scene takes
// the key's default ("render.audio=null": no sound track), or removes a list's entry; a key to
// remove that the scene format does not have is refused (SceneError, UnknownKey), as when set.
void applyOverride(nlohmann::json& document, std::string_view assignment);

// The document every door runs: `initial`, when given (a steady state a command names, steady
// --kind), replaces the scene's initial block, then `overrides` apply in order, so that --set
// initial.phi=45 lands on that block instead of being replaced by it. A document that is no object
// has no initial block to replace: the loader names what it is.
void applyOverrides(nlohmann::json& document, std::span<const std::string> overrides,
                    const std::optional<nlohmann::json>& initial = std::nullopt);

}  // namespace coinroll::scene
