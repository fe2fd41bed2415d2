#pragma once
// What a misspelt name was meant to be: a command (coinroll simulat) or a page control
// (export --controls initial.thet), so that the refusal can say "did you mean".

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace coinroll::cli {

// The Levenshtein distance: single-character insertions, deletions and substitutions from a to b.
std::size_t editDistance(std::string_view a, std::string_view b);

// Edits at most that a misspelt name is taken to be a slip of: two catches a dropped and a swapped
// letter ("simulat", "rendr", "stil", "initial.thet"), and no two commands are that close to each other.
inline constexpr std::size_t kMaxSuggestionEdits = 2;

// The first of `names` nearest to `given` within kMaxSuggestionEdits, and fewer edits than `given`
// has characters (a one-letter slip of nothing is no suggestion); none if no name is that close.
std::optional<std::string> nearestName(std::string_view given, std::span<const std::string> names);

}  // namespace coinroll::cli
