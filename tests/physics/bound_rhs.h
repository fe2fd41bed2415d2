#pragma once
// The seed's right-hand side bound to a model by value, as the integrators take it. Tests own
// their models on the stack, so they cannot use pipeline::CoinRhs (which points at one).

#include "physics/coin_model.h"
#include "physics/dynamics.h"

namespace coinroll::physics {

struct SeedRhs {
  CoinModel model;
  StateVec operator()(double t, const StateVec& y) const { return rhs(model, t, y); }
};

}  // namespace coinroll::physics
