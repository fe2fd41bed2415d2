#include "pipeline/simulation.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "physics/observables.h"
#include "physics/dynamics.h"
#include "physics/flight.h"
#include "physics/quaternion_dynamics.h"
#include "physics/sliding.h"
#include "physics/solid_inertia.h"
#include "physics/steady.h"
#include "physics/validity.h"
#include "scene/scene_loader.h"

namespace coinroll::pipeline {

namespace {

physics::CoinModel modelFrom(const scene::CoinSpec& coin, double g) {
  physics::CoinModel model;
  switch (coin.shape) {
    case scene::Shape::Disk: model = physics::diskModel(coin.mass, coin.radius, g); break;
    case scene::Shape::Ring: model = physics::ringModel(coin.mass, coin.radius, coin.innerRadius, g); break;
    case scene::Shape::Custom:
      model = {.M = coin.mass,
               .a = coin.radius,
               .g = g,
               .I_X = coin.I_X.value(),
               .I_Z = coin.I_Z.value(),
               .rim = {},
               .effects = {}};
      break;
  }
  if (!coin.thickness) return model;
  model.rim = {.thickness = *coin.thickness, .edgeRadius = coin.edgeRadius};
  if (coin.shape != scene::Shape::Custom) {
    // The solid as drawn (docs/rim_inertia.md); custom keeps the moments the scene gives.
    const double hole = coin.shape == scene::Shape::Ring ? coin.innerRadius : 0.0;
    const physics::PrincipalMoments moments =
        physics::filletedCylinderInertia(coin.mass, coin.radius, hole, *coin.thickness, coin.edgeRadius);
    model.I_X = moments.I_X;
    model.I_Z = moments.I_Z;
  }
  return model;
}

physics::Formulation formulationFor(const scene::SceneConfig& scene) {
  const bool landing = scene.coin.thickness && !scene.effects.empty();
  if (scene.sliding) {
    if (scene.solver.formulation == physics::Formulation::EulerAngles) {
      throw scene::SceneError(
          "solver.formulation: \"euler-angles\" does not carry sliding (docs/sliding.md §1: the quaternion formulation "
          "does, the one that reaches a spin-down's landing); use \"quaternion\", the default with \"sliding\": true");
    }
    return physics::Formulation::Quaternion;
  }
  if (!scene.solver.formulation) return landing ? physics::Formulation::Quaternion : physics::Formulation::EulerAngles;
  if (landing && *scene.solver.formulation == physics::Formulation::EulerAngles) {
    throw scene::SceneError(
        "solver.formulation: \"euler-angles\" cannot carry a coin with thickness and effects to its landing (face-down "
        "at "
        "0.05 deg above the floor; the Euler angles are singular at flat and stop at 0.5 deg): use \"quaternion\", the "
        "default for such a scene");
  }
  return *scene.solver.formulation;
}

physics::CoinState steadyState(const physics::CoinModel& model, const scene::SteadyInitial& steady) {
  physics::CoinState s;
  try {
    switch (steady.kind) {
      case scene::SteadyKind::Straight: s = physics::straightRolling(model, steady.omega_Z); break;
      case scene::SteadyKind::Circle:
        s = physics::steadyCircle(model, steady.theta, steady.omega_Z, steady.branch);
        break;
      case scene::SteadyKind::SpinInPlace: s = physics::spinInPlace(model, steady.theta); break;
    }
  } catch (const std::invalid_argument& e) {
    throw scene::SceneError(std::string("initial.steady: ") + e.what());
  }
  // A tilt of 1e-200 deg with no spin asks for a rate past any double: no state to start from.
  if (!std::isfinite(s.omega_X) || !std::isfinite(s.omega_Y) || !std::isfinite(s.omega_Z)) {
    throw scene::SceneError(fmt::format(
        "initial.steady: this steady motion needs rates beyond any number (omega_X = {}, omega_Y = {}, omega_Z = {} "
        "rad/s); tilt it more, or give it more spin",
        s.omega_X, s.omega_Y, s.omega_Z));
  }
  s.phi = steady.phi;
  s.psi = steady.psi;
  s.x = steady.x;
  s.z = steady.z;
  return s;
}

physics::CoinState initialFrom(const physics::CoinModel& model, const scene::InitialSpec& initial) {
  if (const auto* steady = std::get_if<scene::SteadyInitial>(&initial)) return steadyState(model, *steady);
  const auto& e = std::get<scene::ExplicitInitial>(initial);
  return {e.theta, e.phi, e.psi, e.omega_X, e.omega_Y, e.omega_Z, e.x, e.z};
}

// The forward pass of the formulation that will integrate the run, at its start.
physics::Forward startForward(const Simulation& sim) {
  if (sim.formulation == physics::Formulation::Quaternion)
    return physics::forward(sim.model, physics::fromEulerState(sim.initial));
  return physics::forward(sim.model, sim.initial);
}

// m: a given height within this of resting on the rim is on the floor (a height typed from a formula
// rounds in its last digits).
double floorTolerance(const physics::CoinModel& model) { return 1e-9 * model.a; }

// The start of a run with flight: its attitude and rates, its centre at the given height or resting on
// the floor, and its velocity: in the air (v_x, v_y, v_z) with 0 for those not given, on the floor the
// rolling velocity with the given components in its place.
physics::FlightState startingMotion(const Simulation& sim, bool inTheAir) {
  const physics::QuaternionState attitude = physics::fromEulerState(sim.initial);
  const double resting = physics::lowestPointDepth(sim.model, attitude.q);
  physics::FlightState start{.q = attitude.q,
                             .omegaBody = attitude.omegaBody,
                             .centre = {sim.initial.x, sim.initialHeight.value_or(resting), sim.initial.z}};
  start.velocity = inTheAir ? Eigen::Vector3d::Zero() : physics::forward(sim.model, attitude).velocity;
  if (sim.initialVelocity) start.velocity = {sim.initialVelocity->x(), start.velocity.y(), sim.initialVelocity->y()};
  if (sim.initialVerticalVelocity) start.velocity.y() = *sim.initialVerticalVelocity;
  return start;
}

bool startsAboveTheFloor(const Simulation& sim) {
  if (!sim.initialHeight) return false;
  const double resting = physics::lowestPointDepth(sim.model, physics::attitude(sim.initial));
  return *sim.initialHeight - resting > floorTolerance(sim.model);
}

// The floor's hold on a coin starting on it with flight on: refuses a start moving into the floor
// or below it. True when the coin leaves the floor at once.
bool leavesTheFloor(const Simulation& sim) {
  const double resting = physics::lowestPointDepth(sim.model, physics::attitude(sim.initial));
  if (sim.initialHeight && *sim.initialHeight - resting < -floorTolerance(sim.model)) {
    throw scene::SceneError(fmt::format(
        "initial.y: {:.6g} m puts the rim {:.3g} m below the floor; at this tilt the centre rests {:.6g} m up: give "
        "initial.y >= {:.6g}, or leave it out to start on the floor",
        *sim.initialHeight, resting - *sim.initialHeight, resting, resting));
  }
  const physics::FlightState start = startingMotion(sim, false);
  const double rising = physics::pointVelocity(start, physics::lowestPointVector(sim.model, start.q)).y();
  if (rising < -floorTolerance(sim.model) * physics::naturalRate(sim.model)) {
    throw scene::SceneError(fmt::format(
        "initial.v_y: the coin's rim would move into the floor at {:.4g} m/s; a coin on the floor can only rest on "
        "it or leave it: raise v_y by at least that, or start above the floor (initial.y)",
        -rising));
  }
  if (rising > floorTolerance(sim.model) * physics::naturalRate(sim.model)) return true;
  const physics::QuaternionState attitude = physics::fromEulerState(sim.initial);
  const Eigen::Vector2d slip =
      physics::slipOf(sim.model, attitude, Eigen::Vector2d(start.velocity.x(), start.velocity.z()));
  const physics::Forward held =
      slip.norm() > 0
          ? physics::slidingForward(sim.model, {.attitude = attitude, .slip = slip}, sim.model.friction.kinetic,
                                    Eigen::Vector3d(slip.x(), 0, slip.y()).normalized())
          : physics::forward(sim.model, attitude);
  return physics::liftOffMargin(sim.model, held) <= 0;
}

// Events fire on crossings, so a start already outside the model would go unnoticed: refuse it.
void requireValidStart(const Simulation& sim) {
  // A coin starting in the air meets the floor's models only when it lands.
  if (sim.flight && (startsAboveTheFloor(sim) || leavesTheFloor(sim))) return;
  if (physics::hasCorners(sim.model) && sim.initial.theta == 0) {
    throw scene::SceneError(
        "initial.theta: a coin whose rim has corners (coin.edge_radius < thickness / 2) cannot start upright: it "
        "stands on "
        "two corners at once and which one it rolls on is not defined (the corner-switch impact is not modelled); tilt "
        "it "
        "or round the rim fully (edge_radius = thickness / 2)");
  }
  // The flat stop fires on crossing |theta| = tilt; a start beyond it would never cross and run on
  // where the formulation does not hold (the Euler angles from 89.5 deg took the centre 7.5 cm
  // below the floor).
  // "At" the stop includes its last bits: 89 deg given in a scene converts to a double a rounding
  // away from the constant's own.
  if (const physics::FlatStop flat = physics::flatStopFor(sim.model, sim.formulation);
      std::abs(sim.initial.theta) >= flat.tilt * (1 - 1e-12)) {
    const auto degrees = [](double radians) { return radians * 180 / std::numbers::pi; };
    const double quaternionLimit = physics::flatStopFor(sim.model, physics::Formulation::Quaternion).tilt;
    throw scene::SceneError(fmt::format(
        "initial.theta: {:.10g} deg is at or beyond ±{} deg, where this run stops ({}: {}); start inside (-{}, {}) "
        "deg{}",
        degrees(sim.initial.theta), degrees(flat.tilt), physics::eventName(flat.event),
        flat.event == physics::ModelEvent::FaceDown ? "the coin lies on its face" : "the formulation's limit near flat",
        degrees(flat.tilt), degrees(flat.tilt),
        quaternionLimit > flat.tilt
            ? fmt::format(", or use solver.formulation \"quaternion\" (limit ±{} deg)", degrees(quaternionLimit))
            : ""));
  }
  const physics::Forward f = startForward(sim);
  const physics::Reaction& r = f.reaction;
  if (physics::liftOffMargin(sim.model, f) <= 0) {
    throw scene::SceneError(fmt::format(
        "initial: the floor would have to pull the coin down (normal force N = {:.4g} N <= 0): the coin lifts off at "
        "once; lower the spin or the tilt",
        r.N));
  }
  // With sliding on, a start outside the cone or with a slip simply starts sliding, unless that
  // sliding has no unique normal force (the event painleve, which a run can only meet by crossing).
  if (sim.sliding) {
    const physics::QuaternionState start = physics::fromEulerState(sim.initial);
    const Eigen::Vector3d rolling = f.velocity;
    const Eigen::Vector2d velocity = sim.initialVelocity.value_or(Eigen::Vector2d(rolling.x(), rolling.z()));
    const Eigen::Vector2d slip = physics::slipOf(sim.model, start, velocity);
    if (slip.norm() > 0) {
      const Eigen::Vector3d direction = Eigen::Vector3d(slip.x(), 0, slip.y()).normalized();
      const physics::Forward sliding =
          physics::slidingForward(sim.model, {.attitude = start, .slip = slip}, sim.model.friction.kinetic, direction);
      if (!(sliding.normalEffectiveMass > physics::kPainleveMargin)) {
        throw scene::SceneError(
            fmt::format("initial: the coin starts sliding with no unique normal force (Painleve: normal effective mass "
                        "{:.3g} <= {:g} "
                        "with friction {}; docs/sliding.md §3); lower friction, the tilt, or slide the other way",
                        sliding.normalEffectiveMass, physics::kPainleveMargin, sim.model.friction.kinetic));
      }
    }
    return;
  }
  const std::optional<double> mu = sim.model.friction.cone;
  if (mu && physics::slipMargin(sim.model, f, *mu) < 0) {
    throw scene::SceneError(fmt::format(
        "initial: the contact needs friction F = {:.4g} N > mu N = {:.4g} N: the coin slips at once; raise friction or "
        "lower the rates",
        r.F, *mu * r.N));
  }
}

}  // namespace

Simulation buildSimulation(const scene::SceneConfig& scene) {
  Simulation sim;
  sim.model = modelFrom(scene.coin, scene.gravity);
  sim.initial = initialFrom(sim.model, scene.initial);
  sim.solver.method = scene.solver.method;
  sim.solver.rtol = scene.solver.rtol;
  sim.solver.atol = scene.solver.atol;
  sim.solver.dt = scene.solver.dt;
  sim.formulation = formulationFor(scene);
  sim.model.effects = scene.effects;
  sim.model.friction = {.cone = scene.frictionStatic ? scene.frictionStatic : scene.friction,
                        .kinetic = scene.friction.value_or(0)};
  sim.sliding = scene.sliding;
  if (const auto* e = std::get_if<scene::ExplicitInitial>(&scene.initial); e && e->velocity) {
    sim.initialVelocity = Eigen::Vector2d(e->velocity->at(0), e->velocity->at(1));
  }
  if (scene.flight) {
    sim.flight = true;
    sim.model.impact = {.restitution = scene.restitution,
                        .friction = scene.impactFriction.value_or(sim.model.friction.kinetic)};
    if (const auto* e = std::get_if<scene::ExplicitInitial>(&scene.initial)) {
      sim.initialHeight = e->y;
      sim.initialVerticalVelocity = e->v_y;
    }
    sim.stopWhenDecided = scene.stopWhenDecided;
  }
  sim.validityIsTerminal = scene.onInvalid == scene::OnInvalid::Stop;
  sim.duration = scene.duration;
  sim.solver.endTime = scene.duration;
  requireValidStart(sim);
  return sim;
}

std::optional<physics::FlightState> flightStart(const Simulation& simulation) {
  if (!simulation.flight) return std::nullopt;
  if (startsAboveTheFloor(simulation)) return startingMotion(simulation, true);
  if (leavesTheFloor(simulation)) return startingMotion(simulation, false);
  return std::nullopt;
}

std::string steadyStartNote(const scene::SceneConfig& scene) {
  if (scene.effects.empty() || !std::holds_alternative<scene::SteadyInitial>(scene.initial)) return {};
  return "initial.steady is a steady motion of the ideal model; with effects it is only the starting state of a "
         "motion that slows down";
}

std::string describeStop(const RunEvent& hit) {
  using physics::ModelEvent;
  const auto degrees = [](double radians) { return radians * 180 / std::numbers::pi; };
  std::string meaning;
  switch (hit.event) {
    case ModelEvent::CoinFlat:
      meaning = fmt::format(
          "the coin is nearly flat; an ideal run stops at {} deg in the Euler-angle formulation and {} deg in the "
          "quaternion "
          "one (solver.formulation), a thin coin's run with effects at {} deg",
          degrees(physics::kFlatTilt), degrees(physics::kQuaternionFlatTilt), degrees(physics::kSpinDownFlatTilt));
      break;
    case ModelEvent::FaceDown:
      meaning = fmt::format("the coin lies on its face (tilt above the floor below {} deg)", physics::kFaceDownDegrees);
      break;
    case ModelEvent::CornerSwitch:
      meaning =
          "the coin passed upright, where the contact jumps from one corner of the rim to the other (an impact the "
          "rolling model leaves out: \"flight\": true lands the other corner by the impact law; coin.edge_radius = "
          "thickness / 2 rolls through upright)";
      break;
    case ModelEvent::LiftOff: meaning = "the normal force reached zero; the coin would leave the floor"; break;
    case ModelEvent::Slip: meaning = "friction reached mu N; the contact would start slipping"; break;
    case ModelEvent::StickSlip:
      meaning =
          "the coin switched between rolling and sliding more than 1000 times in one simulated second "
          "(stick-slip faster than the model resolves, docs/sliding.md §4)";
      break;
    case ModelEvent::Painleve:
      meaning =
          "the sliding contact has no unique normal force (Painleve's paradox: friction too large for this "
          "attitude; the model would need an impact, docs/sliding.md §3)";
      break;
    case ModelEvent::Rest:
      meaning = fmt::format("the coin landed flat on a face (tilt above the floor below {} deg) and lies there, {} up",
                            physics::kFaceDownDegrees, physics::faceName(physics::faceUp(hit.state.theta)));
      break;
    case ModelEvent::ImpactJam:
      meaning =
          "an impact whose friction keeps the normal impulse from stopping the rim (Painleve's paradox in an "
          "impact, docs/flight.md §3); lower impact_friction";
      break;
    case ModelEvent::Decided:
      meaning = fmt::format(
          "the coin has less energy than standing upright on its rim takes, so it can no longer "
          "turn over: {} up from here on (stop_when_decided)",
          physics::faceName(physics::faceUp(hit.state.theta)));
      break;
    case ModelEvent::OnEdge:
      meaning = fmt::format(
          "the coin stands on its edge: the rocking between the rim's two corners has died away (both move slower "
          "than the bounce-end's speed, or their landings came faster than the run resolves, docs/flight.md §4a) "
          "and the flat band between them lies on the floor, the centre moving at {:.3g} m/s; rolling on the band "
          "is not modelled",
          std::hypot(hit.forward.velocity.x(), hit.forward.velocity.z()));
      break;
  }
  return fmt::format("{} at t = {:.9f} s (theta = {:.4f} deg): {}", physics::eventName(hit.event), hit.t,
                     degrees(hit.state.theta), meaning);
}

}  // namespace coinroll::pipeline
