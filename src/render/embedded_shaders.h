#pragma once
// The files of shaders/, compiled into the binary by cmake/embed_shaders.cmake.

#include <optional>
#include <string_view>

namespace coinroll::render {

std::optional<std::string_view> embeddedShader(std::string_view name);

}  // namespace coinroll::render
