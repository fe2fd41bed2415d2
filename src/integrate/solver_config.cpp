#include "integrate/solver_config.h"

#include <array>

namespace coinroll::integrate {

namespace {

// The registry of methods: a new method is a row here, its Method value, and its step in
// trajectory.h (Trajectory::fixedStep or adaptiveStep).
struct MethodEntry {
  Method method;
  std::string_view name;  // solver.method in a scene file
  bool adaptive;          // error-controlled steps (rtol, atol) rather than fixed ones (dt)
  int errorOrder;         // adaptive: the order of the local error estimate, for the first step's size
};

constexpr std::array<MethodEntry, 5> kMethods = {{
    {Method::Euler, "euler", false, 0},
    {Method::Rk4, "rk4", false, 0},
    {Method::Dopri5, "dopri5", true, 5},
    {Method::Dop853, "dop853", true, 8},
    {Method::Gauss4, "gauss4", false, 0},
}};

constexpr std::array<std::string_view, kMethods.size()> kMethodNames = [] {
  std::array<std::string_view, kMethods.size()> names{};
  for (std::size_t i = 0; i < kMethods.size(); ++i) names[i] = kMethods[i].name;
  return names;
}();

// A loop, not std::ranges::all_of: the libc++ of Emscripten 3.1.6, which builds the WebAssembly core
// (docs/web.md), has no ranges algorithms.
static_assert(
    [] {
      for (std::size_t i = 0; i < kMethods.size(); ++i) {
        if (kMethods[i].method != static_cast<Method>(i)) return false;
      }
      return true;
    }(),
    "kMethods is in the order of the Method enum");

const MethodEntry& entryOf(Method method) { return kMethods.at(static_cast<std::size_t>(method)); }

}  // namespace

std::optional<Method> methodFromName(std::string_view name) {
  for (const MethodEntry& entry : kMethods) {
    if (entry.name == name) return entry.method;
  }
  return std::nullopt;
}

std::string_view nameOf(Method method) { return entryOf(method).name; }

std::span<const std::string_view> methodNames() { return kMethodNames; }

bool isAdaptive(Method method) { return entryOf(method).adaptive; }

int errorEstimateOrder(Method method) { return entryOf(method).errorOrder; }

}  // namespace coinroll::integrate
