#include "cli/nearest_name.h"

#include <algorithm>
#include <vector>

namespace coinroll::cli {

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];  // the distance of a[0, i-1) and b[0, j-1)
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::optional<std::string> nearestName(std::string_view given, std::span<const std::string> names) {
  std::optional<std::string> nearest;
  std::size_t nearestEdits = kMaxSuggestionEdits + 1;
  for (const std::string& name : names) {
    if (const std::size_t edits = editDistance(given, name); edits < nearestEdits && edits < given.size()) {
      nearest = name;
      nearestEdits = edits;
    }
  }
  return nearest;
}

}  // namespace coinroll::cli
