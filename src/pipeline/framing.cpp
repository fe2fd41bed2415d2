#include "pipeline/framing.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics/observables.h"
#include "pipeline/coin_run.h"

namespace coinroll::pipeline {

namespace {

glm::vec3 toGlm(const Eigen::Vector3d& v) { return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())}; }

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
    distance = std::max({distance, std::abs(q.dot(right)) / tanHalfX + towards, std::abs(q.dot(up)) / tanHalfY + towards});
  }
  return 1.06 * distance;
}

}  // namespace

render::CoinPose coinPose(const physics::CoinModel& model, const physics::CoinState& state) {
  const Eigen::Quaterniond q = physics::attitude(state);
  return {toGlm(physics::centreOfMass(model, state)),
          glm::quat(static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()))};
}

Eigen::Vector2d contactOnFloor(const physics::CoinModel& model, const physics::CoinState& state) {
  const Eigen::Vector3d c = physics::contactPoint(model, state);
  return {c.x(), c.z()};
}

std::vector<std::string> hudLines(const physics::CoinModel& model, const physics::CoinState& state, double time,
                                  const std::vector<std::string>& extra) {
  // Near flat psi-dot grows with the contact point's rate while the face itself turns slowly, so
  // the overlay names what it shows: Omega = phi-dot (the contact point round the floor, in Hz,
  // what the ear hears and the eye follows) and the face's own turning omega_Z = psi-dot - phi-dot sin(theta).
  std::vector<std::string> lines = {
      fmt::format("t        {:9.3f} s", time),
      fmt::format("tilt     {:9.2f} deg above floor", 90 - std::abs(state.theta) * 180 / std::numbers::pi),
      fmt::format("contact  {:9.2f} Hz round the floor", std::abs(physics::precessionRate(state)) / (2 * std::numbers::pi)),
      fmt::format("face     {:9.2f} rad/s about its axis", state.omega_Z),
      fmt::format("E        {:9.5f} J", physics::energy(model, state)),
  };
  if (!model.effects.empty()) {
    lines.push_back(fmt::format("P        {:9.3f} mW dissipated", 1e3 * physics::dynamics(model, state).loads.power));
  }
  lines.insert(lines.end(), extra.begin(), extra.end());
  return lines;
}

double traceInterval(double duration) { return std::max(1.0 / 240, duration / 20000); }

MotionSurvey surveyMotion(const Simulation& simulation) {
  CoinRun trajectory(simulation);
  const physics::CoinModel& model = simulation.model;
  MotionSurvey survey;
  survey.lower = survey.upper = physics::centreOfMass(model, simulation.initial);
  const double dt = traceInterval(simulation.duration);
  const long samples = static_cast<long>(std::floor(simulation.duration / dt));
  survey.endTime = simulation.duration;
  for (long k = 0; k <= samples + 1; ++k) {
    const double t = std::min(static_cast<double>(k) * dt, simulation.duration);
    const std::optional<physics::CoinState> y = trajectory.stateAt(t);
    if (!y) break;
    const physics::CoinState s = *y;
    for (const Eigen::Vector3d& p : {physics::centreOfMass(model, s), physics::contactPoint(model, s)}) {
      survey.lower = survey.lower.cwiseMin(p);
      survey.upper = survey.upper.cwiseMax(p);
    }
  }
  if (trajectory.stoppedBy()) {
    survey.stoppedBy = trajectory.stoppedBy();
    survey.endTime = trajectory.stoppedBy()->t;
  }
  return survey;
}

CameraRig::CameraRig(const scene::CameraSpec& spec, const MotionSurvey& survey, const physics::CoinModel& model,
                     int width, int height)
    : spec_(spec), model_(model) {
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
  const int azimuths = spec.mode == "orbit" ? 16 : 1;
  distance_ = 0;
  for (int i = 0; i < azimuths; ++i) {
    const double azimuth = radians(kDefaultAzimuthDegrees) + 2 * std::numbers::pi * i / azimuths;
    distance_ = std::max(distance_, fittingDistance(lower, upper, target_, viewDirection(azimuth, elevation), tanHalfX, tanHalfY));
  }
  distance_ = std::max(distance_, 2.5 * model.a / tanHalfY);  // a coin spinning in place still gets some floor around it
  followDistance_ = 4.0 * model.a / std::min(tanHalfX, tanHalfY);
}

render::CameraView CameraRig::at(double time, const physics::CoinState& state) const {
  render::CameraView view;
  view.fovYDegrees = static_cast<float>(spec_.fovDegrees);
  const double elevation = radians(spec_.elevationDegrees);
  const double azimuth = radians(kDefaultAzimuthDegrees);
  if (spec_.mode == "follow") {
    const Eigen::Vector3d centre = physics::centreOfMass(model_, state);
    const Eigen::Vector3d offset = spec_.eye && spec_.target
                                       ? Eigen::Vector3d(spec_.eye->at(0) - spec_.target->at(0), spec_.eye->at(1) - spec_.target->at(1),
                                                         spec_.eye->at(2) - spec_.target->at(2))
                                       : Eigen::Vector3d(followDistance_ * viewDirection(azimuth, elevation));
    view.target = toGlm(centre);
    view.eye = toGlm(centre + offset);
    return view;
  }
  view.target = toGlm(target_);
  if (spec_.mode == "orbit") {
    const double turn = 2 * std::numbers::pi * time / spec_.orbitPeriod;
    double radius = distance_ * std::cos(elevation), height = distance_ * std::sin(elevation), start = azimuth;
    if (spec_.eye) {
      const Eigen::Vector3d eye(spec_.eye->at(0), spec_.eye->at(1), spec_.eye->at(2));
      const Eigen::Vector3d d = eye - target_;
      radius = std::hypot(d.x(), d.z());
      height = d.y();
      start = std::atan2(d.x(), d.z());
    }
    view.eye = toGlm(target_ + Eigen::Vector3d(radius * std::sin(start + turn), height, radius * std::cos(start + turn)));
    return view;
  }
  view.eye = spec_.eye ? glm::vec3(spec_.eye->at(0), spec_.eye->at(1), spec_.eye->at(2))
                       : toGlm(target_ + distance_ * viewDirection(azimuth, elevation));
  return view;
}

float traceWidthFor(const render::CameraView& view, int height, double coinRadius) {
  const float metresPerPixel =
      2.0f * glm::length(view.eye - view.target) * std::tan(glm::radians(0.5f * view.fovYDegrees)) / static_cast<float>(height);
  return std::max(2.5f * metresPerPixel, 0.05f * static_cast<float>(coinRadius));
}

render::RenderSettings renderSettings(const scene::SceneConfig& scene) {
  render::RenderSettings settings;
  settings.width = scene.render.width;
  settings.height = scene.render.height;
  settings.msaa = scene.render.msaa;
  settings.antialiasing = scene.render.antialiasing == "fxaa" ? render::Antialiasing::Fxaa : render::Antialiasing::Msaa;
  settings.coin.radius = static_cast<float>(scene.coin.radius);
  settings.coin.thickness = static_cast<float>(scene.coin.thickness);
  if (scene.coin.shape == scene::Shape::Ring) {
    // A thin hoop (b = a) is drawn as a band as wide as it is thick, so it stays visible.
    const double band = std::max(scene.coin.thickness, 0.04 * scene.coin.radius);
    settings.coin.innerRadius = static_cast<float>(std::min(scene.coin.innerRadius, scene.coin.radius - band));
  }
  return settings;
}

}  // namespace coinroll::pipeline
