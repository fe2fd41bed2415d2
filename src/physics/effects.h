#pragma once
// The dissipation laws a scene can switch on, one alternative each. Adding a law: its own
// header and source with a parameter struct and loads(law, kinematics), one alternative here,
// one scene key (scene_loader.cpp) and its tests.

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

}  // namespace coinroll::physics
