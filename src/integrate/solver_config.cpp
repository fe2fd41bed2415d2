#include "integrate/solver_config.h"

#include <array>

namespace coinroll::integrate {

namespace {

constexpr std::array<std::string_view, 5> kMethodNames = {"euler", "rk4", "dopri5", "dop853", "gauss4"};

}  // namespace

std::optional<Method> methodFromName(std::string_view name) {
  for (std::size_t i = 0; i < kMethodNames.size(); ++i) {
    if (kMethodNames[i] == name) return static_cast<Method>(i);
  }
  return std::nullopt;
}

std::string_view nameOf(Method method) { return kMethodNames.at(static_cast<std::size_t>(method)); }

std::span<const std::string_view> methodNames() { return kMethodNames; }

bool isAdaptive(Method method) { return method == Method::Dopri5 || method == Method::Dop853; }

}  // namespace coinroll::integrate
