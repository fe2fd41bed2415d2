#include "golden_rule.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace coinroll::testing {

bool goldenTolerant() {
  const char* setting = std::getenv("COINROLL_GOLDEN_TOLERANT");
  const std::string value = setting == nullptr ? "" : setting;
  if (value.empty() || value == "0") return false;
  if (value == "1") return true;
  throw std::invalid_argument(
      "COINROLL_GOLDEN_TOLERANT must be 1 (rounding-level differences pass, for another CPU) "
      "or 0/unset (exact), got '" +
      value + "'");
}

}  // namespace coinroll::testing
