#pragma once

namespace coinroll::physics {

// Which equations of motion run (docs/quaternion_formulation.md): the seed's Euler angles, or the
// attitude quaternion that has no coordinate singularity at theta = 90 degrees.
enum class Formulation { EulerAngles, Quaternion };

}  // namespace coinroll::physics
