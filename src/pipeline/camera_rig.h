#pragma once
// The scene's render.camera turned into a view per time, placed from the motion survey.

#include <Eigen/Core>

#include <optional>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "pipeline/motion_survey.h"
#include "render/frame_snapshot.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// Fixed frames the survey box; orbit keeps the same distance and circles the box once per orbit
// period; follow tracks the coin. An eye or target given in the scene overrides the framing.
class CameraRig {
 public:
  // `width` x `height`: the picture in pixels, whose aspect ratio the framing fits. `towardsEye`
  // (unit, from the target to the eye): the direction a fixed camera without an eye frames the box
  // from, by default 20 degrees round from +z at the spec's elevation.
  CameraRig(const scene::CameraSpec& spec, const MotionSurvey& survey, const physics::CoinModel& model, int width,
            int height, const std::optional<Eigen::Vector3d>& towardsEye = std::nullopt);
  // The view at simulated `time` (s) with the coin at `state`.
  render::CameraView at(double time, const Eigen::Vector3d& centreOfMass) const;

 private:
  scene::CameraSpec spec_;
  Eigen::Vector3d target_;
  Eigen::Vector3d towardsEye_;  // unit, the framing's direction from the target to the eye
  double distance_ = 1;         // m
  double followDistance_ = 1;   // m
};

}  // namespace coinroll::pipeline
