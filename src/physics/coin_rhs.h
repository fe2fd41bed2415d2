#pragma once
// Each formulation's right-hand side bound to a model held by value, in the f(t, y) shape the
// integrators take. A state of the formulation's own size integrates the motion; a state one
// longer also integrates, as its last component, the energy the effects have dissipated (J) at
// the rate of their declared power, so that energy + dissipated can be checked against the start.

#include <Eigen/Core>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/dynamics.h"
#include "physics/formulation.h"
#include "physics/quaternion_dynamics.h"

namespace coinroll::physics {

template <Formulation F>
inline constexpr int kMotionSize = F == Formulation::EulerAngles ? kStateSize : kQuaternionStateSize;

template <Formulation F>
struct CoinRhs {
  CoinModel model;

  template <int N>
  Eigen::Matrix<double, N, 1> operator()(double t, const Eigen::Matrix<double, N, 1>& y) const {
    constexpr int kMotion = kMotionSize<F>;
    static_assert(N == kMotion || N == kMotion + 1, "a formulation's state, optionally with the dissipated energy");
    if constexpr (N == kMotion) {
      if constexpr (F == Formulation::EulerAngles)
        return rhs(model, t, y);
      else
        return quaternionRhs(model, t, y);
    } else {
      const Eigen::Matrix<double, kMotion, 1> motion = y.template head<kMotion>();
      Eigen::Matrix<double, N, 1> dy;
      if constexpr (F == Formulation::EulerAngles) {
        const Rates r = rates(model, motion);
        dy << r.dy, r.power;
      } else {
        const QuaternionRates r = quaternionRates(model, motion);
        dy << r.dy, r.power;
      }
      return dy;
    }
  }
};

}  // namespace coinroll::physics
