#include "pipeline/camera_rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics/observables.h"

namespace coinroll::pipeline {

namespace {

glm::vec3 toGlm(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

// The default camera looks at the coin's initial face (from +z) turned 20 degrees, so the
// rolling direction (along x at phi = 0) runs across the picture with some depth.
constexpr double kDefaultAzimuthDegrees = 20;

Eigen::Vector3d viewDirection(double azimuth, double elevation) {
  return {std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation)};
}

// The smallest eye distance from `target` along `towardsEye` at which every corner of the box
// lies inside the field of view, with a 6 % margin: for a corner at offset q, its sideways
// extents must not exceed tan(half fov) times its depth D - q . towardsEye.
double fittingDistance(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper, const Eigen::Vector3d& target,
                       const Eigen::Vector3d& towardsEye, double tanHalfX, double tanHalfY) {
  const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(towardsEye).normalized();
  const Eigen::Vector3d up = towardsEye.cross(right);
  double distance = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? upper.x() : lower.x(), (corner & 2) ? upper.y() : lower.y(),
                            (corner & 4) ? upper.z() : lower.z());
    const Eigen::Vector3d q = p - target;
    const double towards = q.dot(towardsEye);
    distance =
        std::max({distance, std::abs(q.dot(right)) / tanHalfX + towards, std::abs(q.dot(up)) / tanHalfY + towards});
  }
  return 1.06 * distance;
}

}  // namespace

CameraRig::CameraRig(const scene::CameraSpec& spec, const MotionSurvey& survey, const physics::CoinModel& model,
                     int width, int height, const std::optional<Eigen::Vector3d>& towardsEye)
    : spec_(spec),
      towardsEye_(towardsEye.value_or(viewDirection(radians(kDefaultAzimuthDegrees), radians(spec.elevationDegrees)))) {
  // The box of all centres and contact points, widened by the coin itself, from the floor up.
  const Eigen::Vector3d margin(model.a, 0, model.a);
  Eigen::Vector3d lower = survey.lower - margin, upper = survey.upper + margin;
  lower.y() = 0;
  upper.y() = std::max(upper.y(), model.a) + 0.2 * model.a;
  target_ = spec.target ? Eigen::Vector3d(spec.target->at(0), spec.target->at(1), spec.target->at(2))
                        : Eigen::Vector3d(0.5 * (lower + upper));
  const double tanHalfY = std::tan(0.5 * radians(spec.fovDegrees));
  const double tanHalfX = tanHalfY * width / height;
  const double elevation = radians(spec.elevationDegrees);
  // An orbit sees the box from every side: fit it from 16 azimuths and keep the farthest.
  if (spec.mode == scene::CameraMode::Orbit) {
    distance_ = 0;
    for (int i = 0; i < 16; ++i) {
      const double azimuth = radians(kDefaultAzimuthDegrees) + 2 * std::numbers::pi * i / 16;
      distance_ = std::max(
          distance_, fittingDistance(lower, upper, target_, viewDirection(azimuth, elevation), tanHalfX, tanHalfY));
    }
  } else {
    distance_ = fittingDistance(lower, upper, target_, towardsEye_, tanHalfX, tanHalfY);
  }
  distance_ =
      std::max(distance_, 2.5 * model.a / tanHalfY);  // a coin spinning in place still gets some floor around it
  followDistance_ = 4.0 * model.a / std::min(tanHalfX, tanHalfY);
}

render::CameraView CameraRig::at(double time, const Eigen::Vector3d& centre) const {
  render::CameraView view;
  view.fovYDegrees = static_cast<float>(spec_.fovDegrees);
  const double elevation = radians(spec_.elevationDegrees);
  const double azimuth = radians(kDefaultAzimuthDegrees);
  if (spec_.mode == scene::CameraMode::Follow) {
    const Eigen::Vector3d offset =
        spec_.eye && spec_.target
            ? Eigen::Vector3d(spec_.eye->at(0) - spec_.target->at(0), spec_.eye->at(1) - spec_.target->at(1),
                              spec_.eye->at(2) - spec_.target->at(2))
            : Eigen::Vector3d(followDistance_ * viewDirection(azimuth, elevation));
    view.target = toGlm(centre);
    view.eye = toGlm(centre + offset);
    return view;
  }
  view.target = toGlm(target_);
  if (spec_.mode == scene::CameraMode::Orbit) {
    const double turn = 2 * std::numbers::pi * time / spec_.orbitPeriod;
    double radius = distance_ * std::cos(elevation), height = distance_ * std::sin(elevation), start = azimuth;
    if (spec_.eye) {
      const Eigen::Vector3d eye(spec_.eye->at(0), spec_.eye->at(1), spec_.eye->at(2));
      const Eigen::Vector3d d = eye - target_;
      radius = std::hypot(d.x(), d.z());
      height = d.y();
      start = std::atan2(d.x(), d.z());
    }
    view.eye =
        toGlm(target_ + Eigen::Vector3d(radius * std::sin(start + turn), height, radius * std::cos(start + turn)));
    return view;
  }
  view.eye = spec_.eye ? glm::vec3(spec_.eye->at(0), spec_.eye->at(1), spec_.eye->at(2))
                       : toGlm(target_ + distance_ * towardsEye_);
  return view;
}

}  // namespace coinroll::pipeline
