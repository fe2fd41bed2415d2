#include "cli/terminal_text.h"

#include <fmt/format.h>

namespace coinroll::cli {

std::string printable(std::string_view text) {
  std::string shown;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') shown += "\\n";
    else if ((byte < 0x20 && c != '\t') || byte == 0x7f) shown += fmt::format("\\x{:02x}", byte);
    else shown += c;
  }
  return shown;
}

}  // namespace coinroll::cli
