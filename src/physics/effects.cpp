#include "physics/effects.h"

namespace coinroll::physics {

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// C++20 deduces this by itself; clang 14 (the fuzz build) does not yet.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

std::string_view typeName(const Effect& effect) {
  return std::visit(Overloaded{[](const AirDrag&) { return std::string_view("air_drag"); },
                               [](const RollingResistance&) { return std::string_view("rolling_resistance"); },
                               [](const SpinFriction&) { return std::string_view("spin_friction"); }},
                    effect);
}

Loads totalLoads(std::span<const Effect> effects, const ContactKinematics& k) {
  Loads sum;
  for (const Effect& effect : effects) sum += std::visit([&k](const auto& law) { return loads(law, k); }, effect);
  return sum;
}

}  // namespace coinroll::physics
