#include "pipeline/simulation.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "physics/observables.h"
#include "physics/quaternion_dynamics.h"
#include "physics/steady.h"
#include "physics/validity.h"
#include "scene/scene_loader.h"

namespace coinroll::pipeline {

namespace {

physics::CoinModel modelFrom(const scene::CoinSpec& coin, double g) {
  switch (coin.shape) {
    case scene::Shape::Disk: return physics::diskModel(coin.mass, coin.radius, g);
    case scene::Shape::Ring: return physics::ringModel(coin.mass, coin.radius, coin.innerRadius, g);
    case scene::Shape::Custom:
      return {.M = coin.mass, .a = coin.radius, .g = g, .I_X = coin.I_X.value(), .I_Z = coin.I_Z.value(), .effects = {}};
  }
  throw std::logic_error("unhandled coin shape");
}

physics::CoinState steadyState(const physics::CoinModel& model, const scene::SteadyInitial& steady) {
  physics::CoinState s;
  try {
    switch (steady.kind) {
      case scene::SteadyKind::Straight: s = physics::straightRolling(steady.omega_Z); break;
      case scene::SteadyKind::Circle: s = physics::steadyCircle(model, steady.theta, steady.omega_Z, steady.branch); break;
      case scene::SteadyKind::SpinInPlace: s = physics::spinInPlace(model, steady.theta); break;
    }
  } catch (const std::invalid_argument& e) {
    throw scene::SceneError(std::string("initial.steady: ") + e.what());
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

// Events fire on crossings, so a start already outside the model would go unnoticed: refuse it.
void requireValidStart(const Simulation& sim) {
  const physics::Reaction r = physics::reaction(sim.model, sim.initial);
  if (physics::liftOffMargin(sim.model, sim.initial) <= 0) {
    throw scene::SceneError(fmt::format(
        "initial: the floor would have to pull the coin down (normal force N = {:.4g} N <= 0): the coin lifts off at "
        "once; lower the spin or the tilt", r.N));
  }
  if (sim.friction && physics::slipMargin(sim.model, sim.initial, *sim.friction) < 0) {
    throw scene::SceneError(fmt::format(
        "initial: the contact needs friction F = {:.4g} N > mu N = {:.4g} N: the coin slips at once; raise friction or "
        "lower the rates", r.F, *sim.friction * r.N));
  }
}

}  // namespace

Simulation buildSimulation(const scene::SceneConfig& scene) {
  Simulation sim;
  sim.model = modelFrom(scene.coin, scene.gravity);
  sim.initial = initialFrom(sim.model, scene.initial);
  const std::optional<integrate::Method> method = integrate::methodFromName(scene.solver.method);
  if (!method) throw scene::SceneError("solver.method: unknown method '" + scene.solver.method + "'");
  sim.solver.method = *method;
  sim.solver.rtol = scene.solver.rtol;
  sim.solver.atol = scene.solver.atol;
  sim.solver.dt = scene.solver.dt;
  sim.formulation = scene.solver.formulation;
  sim.model.effects = scene.effects;
  sim.friction = scene.friction;
  sim.validityIsTerminal = scene.onInvalid == scene::OnInvalid::Stop;
  sim.duration = scene.duration;
  requireValidStart(sim);
  return sim;
}

std::string steadyStartNote(const scene::SceneConfig& scene) {
  if (scene.effects.empty() || !std::holds_alternative<scene::SteadyInitial>(scene.initial)) return {};
  return "initial.steady is a steady motion of the ideal model; with effects it is only the starting state of a "
         "motion that slows down";
}

std::string describeStop(const integrate::EventHit<physics::kStateSize>& hit) {
  const std::string flat = fmt::format(
      "the coin is nearly flat; an ideal run stops at {} deg in the Euler-angle formulation and {} deg in the quaternion "
      "one (solver.formulation), a run with effects at {} deg",
      physics::kFlatTilt * 180 / std::numbers::pi, physics::kQuaternionFlatTilt * 180 / std::numbers::pi,
      physics::kSpinDownFlatTilt * 180 / std::numbers::pi);
  const std::string meaning = hit.name == "coin-flat" ? flat
                              : hit.name == "lift-off" ? "the normal force reached zero; the coin would leave the floor"
                              : hit.name == "slip"     ? "friction reached mu N; the contact would start slipping"
                                                       : "event";
  return fmt::format("{} at t = {:.9f} s (theta = {:.4f} deg): {}", hit.name, hit.t,
                     hit.y[physics::kTheta] * 180 / std::numbers::pi, meaning);
}

}  // namespace coinroll::pipeline
