#include "physics/effects.h"

#include <algorithm>
#include <type_traits>

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

namespace {

bool readsNormalForce(const Effect& effect) {
  return std::visit([](const auto& law) { return std::decay_t<decltype(law)>::kReadsNormalForce; }, effect);
}

Loads loadsOf(const Effect& effect, const ContactKinematics& k) {
  return std::visit([&k](const auto& law) { return loads(law, k); }, effect);
}

}  // namespace

NormalForceLoads::NormalForceLoads(std::span<const Effect> effects, const ContactKinematics& k)
    : effects_(effects), kinematics_(k) {
  for (std::size_t i = 0; i < std::min(effects.size(), kRemembered); ++i) {
    if (!readsNormalForce(effects[i])) fixed_[i] = loadsOf(effects[i], k);
  }
}

Loads NormalForceLoads::at(double N) const {
  ContactKinematics atN = kinematics_;
  atN.N = N;
  Loads sum;
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    const bool fixed = i < kRemembered && !readsNormalForce(effects_[i]);
    sum += fixed ? fixed_[i] : loadsOf(effects_[i], atN);
  }
  return sum;
}

Loads totalLoads(std::span<const Effect> effects, const ContactKinematics& k) {
  Loads sum;
  for (const Effect& effect : effects) sum += loadsOf(effect, k);
  return sum;
}

}  // namespace coinroll::physics
