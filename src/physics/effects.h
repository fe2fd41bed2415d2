#pragma once
// The dissipation laws a scene can switch on, one alternative of Effect each, and their sum.
// Adding a law: its own header and source (listed in CMakeLists.txt) with a parameter struct and
// loads(law, kinematics) returning its couple and power >= 0; an alternative of Effect and its
// name in typeName (effects.cpp); its rows in the scene schema (src/scene/scene_schema.cpp, whose
// kEffectTypeNames must follow Effect's order) and its read in scene_loader.cpp, then docs/scene.md
// regenerated (coinroll schema --markdown); its bad-input cases in tests/cli/bad_inputs.py (docs/bad_inputs.md
// is generated from them); its tests in tests/physics/effects_test.cpp (power = -torque . omega
// is checked for every law). A couple that depends on N must have no part along e_X: the normal
// force's two passes (dynamics.cpp, quaternion_dynamics.cpp) are exact only then (tested).

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <variant>

#include "physics/air_drag.h"
#include "physics/contact_kinematics.h"
#include "physics/rolling_resistance.h"
#include "physics/spin_friction.h"

namespace coinroll::physics {

using Effect = std::variant<AirDrag, RollingResistance, SpinFriction>;

// The scene file's "type" of each law: "air_drag", "rolling_resistance", "spin_friction".
std::string_view typeName(const Effect& effect);

// The sum of every law's couple and power.
Loads totalLoads(std::span<const Effect> effects, const ContactKinematics& k);

// totalLoads of one state at the normal forces its passes try (and, sliding, at every friction
// direction the creep's search tries): only N changes between the calls, so a law that does not read
// it (kReadsNormalForce false: air drag) is evaluated once. The same sum, in the same order, to the bit.
class NormalForceLoads {
 public:
  NormalForceLoads(std::span<const Effect> effects, const ContactKinematics& k);
  Loads at(double N) const;

 private:
  static constexpr std::size_t kRemembered = 4;  // laws past these are evaluated at every call
  std::span<const Effect> effects_;
  ContactKinematics kinematics_;
  std::array<Loads, kRemembered> fixed_;  // the N-free laws' loads, by the law's place
};

}  // namespace coinroll::physics
