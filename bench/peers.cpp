// The peers of the work-precision benchmark, each driven as its documentation recommends for a
// non-stiff problem and each calling the same CoinRhs: Boost.Odeint's controlled Dormand-Prince
// 5(4) and Fehlberg 7(8) and its Bulirsch-Stoer extrapolation, and SUNDIALS CVODE's variable-order
// Adams method with fixed-point iteration (no Jacobian). Tolerance: rtol = atol = `tolerance`
// for every solver, ours included.

// GCC 12 flags odeint's copy of its default-constructed scratch arrays (std::array members
// that the stepper fills before reading) as use of uninitialised values; a false positive in a
// third-party header that SYSTEM cannot silence because it appears only after inlining.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/numeric/odeint.hpp>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <array>
#include <memory>

#include "work_precision.h"

namespace coinroll::bench {

namespace {

using physics::StateVec;
namespace odeint = boost::numeric::odeint;

// Odeint's favourite state: a plain array with its default range algebra.
using BoostState = std::array<double, physics::kStateSize>;

struct BoostSystem {
  const CoinRhs* rhs;
  void operator()(const BoostState& x, BoostState& dxdt, double t) const {
    Eigen::Map<StateVec>(dxdt.data()) = (*rhs)(t, StateVec(Eigen::Map<const StateVec>(x.data())));
  }
};

BoostState toBoost(const physics::CoinState& s) {
  BoostState x;
  Eigen::Map<StateVec>(x.data()) = physics::toVector(s);
  return x;
}

constexpr double kFirstStep = 1e-4;  // s; every odeint stepper adapts it from there

template <class Stepper>
RunResult runOdeint(Stepper stepper, const Case& c, bool trackEnergy) {
  RunResult result;
  const CoinRhs rhs{c.model, &result.rhsEvaluations};
  BoostState x = toBoost(c.start);
  auto observeEnergy = [&](const BoostState& state, double) {
    result.maxEnergyError = std::max(result.maxEnergyError, energyError(c, Eigen::Map<const StateVec>(state.data())));
  };
  try {
    result.steps =
        trackEnergy ? odeint::integrate_adaptive(stepper, BoostSystem{&rhs}, x, 0.0, c.tEnd, kFirstStep, observeEnergy)
                    : odeint::integrate_adaptive(stepper, BoostSystem{&rhs}, x, 0.0, c.tEnd, kFirstStep);
  } catch (const std::exception&) {
    result.failed = true;
  }
  result.yEnd = Eigen::Map<const StateVec>(x.data());
  result.rejectedSteps = -1;  // integrate_adaptive does not report rejections
  result.failed = result.failed || !result.yEnd.allFinite();
  return result;
}

// SUNDIALS handles, each freed by its own function.
struct ContextFree {
  void operator()(SUNContext context) const { SUNContext_Free(&context); }
};
struct VectorFree {
  void operator()(N_Vector vector) const { N_VDestroy(vector); }
};
struct CvodeFree {
  void operator()(void* memory) const { CVodeFree(&memory); }
};
struct SolverFree {
  void operator()(SUNNonlinearSolver solver) const { SUNNonlinSolFree(solver); }
};

int cvodeRhs(sunrealtype t, N_Vector y, N_Vector ydot, void* userData) {
  const CoinRhs& rhs = *static_cast<const CoinRhs*>(userData);
  Eigen::Map<StateVec>(N_VGetArrayPointer(ydot)) = rhs(t, StateVec(Eigen::Map<const StateVec>(N_VGetArrayPointer(y))));
  return 0;
}

}  // namespace

RunResult boostDopri5(const Case& c, double tolerance, bool trackEnergy) {
  return runOdeint(odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<BoostState>()), c,
                   trackEnergy);
}

RunResult boostFehlberg78(const Case& c, double tolerance, bool trackEnergy) {
  return runOdeint(odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_fehlberg78<BoostState>()), c,
                   trackEnergy);
}

RunResult boostBulirschStoer(const Case& c, double tolerance, bool trackEnergy) {
  return runOdeint(odeint::bulirsch_stoer<BoostState>(tolerance, tolerance), c, trackEnergy);
}

#pragma GCC diagnostic pop

RunResult cvodeAdams(const Case& c, double tolerance, bool trackEnergy) {
  RunResult result;
  CoinRhs rhs{c.model, &result.rhsEvaluations};
  SUNContext rawContext = nullptr;
  if (SUNContext_Create(nullptr, &rawContext) != 0) throw std::runtime_error("SUNContext_Create failed");
  const std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextFree> context(rawContext);
  const std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorFree> y(N_VNew_Serial(physics::kStateSize, rawContext));
  Eigen::Map<StateVec>(N_VGetArrayPointer(y.get())) = physics::toVector(c.start);
  // Declared before the integrator so it is freed after it: CVODE only borrows it.
  const std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, SolverFree> fixedPoint(
      SUNNonlinSol_FixedPoint(y.get(), 0, rawContext));
  const std::unique_ptr<void, CvodeFree> cvode(CVodeCreate(CV_ADAMS, rawContext));
  void* memory = cvode.get();
  const bool configured =
      CVodeInit(memory, cvodeRhs, 0.0, y.get()) == CV_SUCCESS &&
      CVodeSStolerances(memory, tolerance, tolerance) == CV_SUCCESS && CVodeSetUserData(memory, &rhs) == CV_SUCCESS &&
      CVodeSetNonlinearSolver(memory, fixedPoint.get()) == CV_SUCCESS &&
      CVodeSetMaxNumSteps(memory, 100'000'000) == CV_SUCCESS && CVodeSetStopTime(memory, c.tEnd) == CV_SUCCESS &&
      CVodeSetErrFile(memory, nullptr) == CV_SUCCESS;
  if (!configured) throw std::runtime_error("CVODE setup failed");
  sunrealtype t = 0;
  int flag = CV_SUCCESS;
  if (trackEnergy) {
    while (t < c.tEnd && flag >= 0) {
      flag = CVode(memory, c.tEnd, y.get(), &t, CV_ONE_STEP);
      result.maxEnergyError =
          std::max(result.maxEnergyError, energyError(c, Eigen::Map<const StateVec>(N_VGetArrayPointer(y.get()))));
    }
  } else {
    flag = CVode(memory, c.tEnd, y.get(), &t, CV_NORMAL);
  }
  long steps = 0, errorTestFailures = 0;
  CVodeGetNumSteps(memory, &steps);
  CVodeGetNumErrTestFails(memory, &errorTestFailures);
  result.steps = steps;
  result.rejectedSteps = errorTestFailures;
  result.yEnd = Eigen::Map<const StateVec>(N_VGetArrayPointer(y.get()));
  result.failed = flag < 0 || !result.yEnd.allFinite();
  return result;
}

}  // namespace coinroll::bench
